// prepare_refinement_flags_consistently (bodies/consistent_refinement_flags.h)
// must give a distributed mesh the flags a serial mesh gets from deal.II's
// rules, on any number of ranks.
//
// A graded square: 3 global refinements, the lower half refined once more
// and the lower quarter once more again (levels 5, 4, 3 one above the
// other; on 2 ranks p4est's partition runs through the level-4 band).
// Every cell is flagged for coarsening except a few cells flagged for
// refinement near (0.8, 0.8). The same flags are set on a serial
// Triangulation with the smoothing a p4est mesh has (at most one level
// between cells sharing a vertex), coarsened and refined there: the truth.
// The distributed mesh must end with the serial mesh's cells (CellIds, all
// ranks). With deal.II 9.4's own prepare_coarsening_and_refinement(), 2
// ranks kept families beside the partition boundary (see the header):
// the test prints that count too, which is the serial one on 1 rank only.

#include <deal.II/distributed/tria.h>

#include <deal.II/grid/grid_generator.h>

#include <coulomb_adapt/bodies/consistent_refinement_flags.h>

#include "test_utilities.h"

#include <set>

using namespace coulomb_adapt;

namespace
{
  template <typename Tria>
  void
  build_graded_square(Tria &tria)
  {
    GridGenerator::hyper_cube(tria);
    tria.refine_global(3);
    for (const double y_max : {0.5, 0.25})
      {
        for (const auto &cell : tria.active_cell_iterators())
          if (!cell->is_artificial() && cell->center()[1] < y_max)
            cell->set_refine_flag();
        tria.execute_coarsening_and_refinement();
      }
  }



  template <typename Tria>
  void
  flag_cells(Tria &tria)
  {
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          if (cell->center().distance(Point<2>(0.8, 0.8)) < 0.1)
            cell->set_refine_flag();
          else
            cell->set_coarsen_flag();
        }
  }



  std::set<CellId>
  all_active_cells(const parallel::distributed::Triangulation<2> &tria)
  {
    std::vector<CellId> owned;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        owned.push_back(cell->id());
    std::set<CellId> all;
    for (const auto &part :
         Utilities::MPI::all_gather(tria.get_communicator(), owned))
      all.insert(part.begin(), part.end());
    return all;
  }



  std::set<CellId>
  active_cells(const Triangulation<2> &tria)
  {
    std::set<CellId> all;
    for (const auto &cell : tria.active_cell_iterators())
      all.insert(cell->id());
    return all;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  Triangulation<2> serial(Triangulation<2>::limit_level_difference_at_vertices);
  build_graded_square(serial);
  out << "graded mesh: " << serial.n_active_cells() << " cells" << std::endl;
  flag_cells(serial);
  serial.execute_coarsening_and_refinement();
  const std::set<CellId> truth = active_cells(serial);
  out << "serial mesh after the flags: " << truth.size() << " cells"
      << std::endl;

  for (const bool consistent : {false, true})
    {
      parallel::distributed::Triangulation<2> tria(comm);
      build_graded_square(tria);
      flag_cells(tria);
      if (consistent)
        prepare_refinement_flags_consistently(tria);
      else
        tria.prepare_coarsening_and_refinement();
      tria.execute_coarsening_and_refinement();
      const std::set<CellId> cells = all_active_cells(tria);
      if (consistent)
        {
          out << "consistent flags: " << cells.size()
              << " cells, the serial mesh's: "
              << (cells == truth ? "yes" : "no") << std::endl;
          AssertThrow(cells == truth,
                      ExcMessage("the distributed mesh differs from the "
                                 "serial one"));
        }
      else
        // 1 rank: the serial mesh; 2 ranks: more cells (its .output).
        out << "deal.II's own flags: " << cells.size() << " cells" << std::endl;
    }
}
