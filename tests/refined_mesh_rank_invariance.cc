// A locally refined adaptive run gives the same meshes on 1 and 2 ranks.
//
// prm/punch.prm with Q2 elements, 'Strategy = refine', epsilon_0 = 0.5 %:
// the second adaptation step coarsens thousands of cells, and on 2 ranks
// the partition boundary of cycle 1 runs through a patch of them. Before
// the owners' flags were copied to the ghost cells
// (bodies/consistent_refinement_flags.h), deal.II's smoothing kept a
// family there on 2 ranks: 20,980 DoFs in cycle 2 instead of 20,540.
// Each cycle's cells per body, DoFs, Newton steps and epsilon are printed
// and a fingerprint of each body's mesh: the sums over the active cells of
// x^2 and y of their centres (the scene is symmetric in x), which a
// changed cell moves. The 2-rank output must be the 1-rank one.

#include "program_run.h"
#include "test_utilities.h"

#include <iomanip>

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const testing::ProgramRun run({{"Finite elements/Polynomial degree", "2"},
                                 {"Adaptation/Strategy", "refine"},
                                 {"Adaptation/Target error", "0.5"},
                                 {"Adaptation/Number of cycles", "8"},
                                 {"Output/Write VTU", "false"},
                                 {"Output/Output directory",
                                  "output_refined_mesh_rank_invariance"}},
                                testing::example_file("punch.prm"));

  for (const auto &cycle : run.summary["cycles"])
    out << "cycle " << cycle["cycle"].get<int>() << ": "
        << cycle["n_dofs"].get<long>() << " DoFs, "
        << cycle["newton_iterations"].get<int>() << " Newton steps, epsilon "
        << std::setprecision(4) << 100 * cycle["epsilon"].get<double>() << " %"
        << std::endl;
  for (unsigned int b = 0; b < 2; ++b)
    {
      const auto &tria   = run.problem->body(b).triangulation();
      double      sum_x2 = 0, sum_y = 0;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            sum_x2 += cell->center()[0] * cell->center()[0];
            sum_y += cell->center()[1];
          }
      out << "final mesh of body " << b + 1 << ": "
          << tria.n_global_active_cells() << " cells, sums of x^2 and y "
          << std::setprecision(10)
          << Utilities::MPI::sum(sum_x2, MPI_COMM_WORLD) << " and "
          << Utilities::MPI::sum(sum_y, MPI_COMM_WORLD) << std::endl;
    }
}
