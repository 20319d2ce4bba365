// CoarseCellIndexedTriangulation (bodies/coarse_cell_indexed_triangulation.h)
// looks coarse cells up in a table instead of deal.II's binary search; the
// triangulation it builds from a description must be deal.II's
// parallel::fullydistributed::Triangulation's, cell for cell.
//
// A serial triangle mesh with one coarse cell per triangle (as a remeshed
// body: 2 x 40 x 25 triangles), boundary ids on the four sides,
// a manifold id on the top side's lines, is partitioned over the
// ranks; the description's cell infos are shuffled (deal.II sorts them by
// coarse cell index, through the lookup: a wrong index would give a cell
// another's subdomain and boundary ids) and both triangulations are built
// from it. Every cell, in order, must have the same vertices, subdomain
// id, material id, manifold ids, face boundary ids and CellId, and
// create_cell_iterator(id) (the lookup) must give the cell back on both.
// The counts printed are sums over the ranks: 1 and 2 ranks print the
// same.

#include <deal.II/distributed/fully_distributed_tria.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <coulomb_adapt/bodies/coarse_cell_indexed_triangulation.h>

#include "test_utilities.h"

#include <algorithm>
#include <random>

using namespace coulomb_adapt;

namespace
{
  // What must agree between the two triangulations for one active cell.
  bool
  same_cell(const Triangulation<2>::active_cell_iterator &a,
            const Triangulation<2>::active_cell_iterator &b)
  {
    bool same = a->id() == b->id() && a->subdomain_id() == b->subdomain_id() &&
                a->material_id() == b->material_id() &&
                a->manifold_id() == b->manifold_id() &&
                a->n_vertices() == b->n_vertices();
    for (unsigned int v = 0; same && v < a->n_vertices(); ++v)
      same = a->vertex(v).distance(b->vertex(v)) == 0 &&
             a->vertex_index(v) == b->vertex_index(v);
    for (const unsigned int f : a->face_indices())
      same = same && a->face(f)->boundary_id() == b->face(f)->boundary_id() &&
             a->face(f)->manifold_id() == b->face(f)->manifold_id();
    return same;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  Triangulation<2> serial;
  GridGenerator::subdivided_hyper_rectangle_with_simplices(
    serial, {40, 25}, Point<2>(0, 0), Point<2>(2, 1));
  // Boundary ids 0 to 3 on the sides x = 0, x = 2, y = 0, y = 1 (deal.II
  // 9.4 does not colorize simplex meshes), manifold id 7 on the top.
  for (const auto &cell : serial.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        {
          const Point<2> c = cell->face(f)->center();
          const auto     id = static_cast<types::boundary_id>(
            c[0] < 1e-12 ? 0 : c[0] > 2 - 1e-12 ? 1 : c[1] < 1e-12 ? 2 : 3);
          cell->face(f)->set_boundary_id(id);
          if (id == 3)
            cell->face(f)->set_manifold_id(7);
        }
  GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(comm),
                                     serial);
  auto description = TriangulationDescription::Utilities::
    create_description_from_triangulation(serial, comm);
  std::mt19937 random(1);
  for (auto &level : description.cell_infos)
    std::shuffle(level.begin(), level.end(), random);

  parallel::fullydistributed::Triangulation<2> reference(comm);
  CoarseCellIndexedTriangulation               indexed(comm);
  reference.create_triangulation(description);
  indexed.create_triangulation(description);

  unsigned int n_owned = 0, n_different = 0, n_not_found = 0;
  bool         same_count = reference.n_active_cells() == indexed.n_active_cells();
  if (same_count)
    for (auto a = reference.begin_active(), b = indexed.begin_active();
         a != reference.end();
         ++a, ++b)
      {
        n_owned += a->is_locally_owned();
        n_different += !same_cell(a, b);
        if (!a->is_artificial())
          n_not_found += reference.create_cell_iterator(a->id()) != a ||
                         indexed.create_cell_iterator(b->id()) != b;
      }
  same_count = Utilities::MPI::min(static_cast<unsigned int>(same_count), comm);
  n_owned     = Utilities::MPI::sum(n_owned, comm);
  n_different = Utilities::MPI::sum(n_different, comm);
  n_not_found = Utilities::MPI::sum(n_not_found, comm);

  out << "serial mesh: " << serial.n_active_cells() << " triangles" << std::endl
      << "same number of cells on every rank: " << (same_count ? "yes" : "no")
      << std::endl
      << "owned cells, all ranks: " << n_owned << std::endl
      << "cells that differ: " << n_different << std::endl
      << "cells create_cell_iterator(id) does not find: " << n_not_found
      << std::endl;
  AssertThrow(same_count && n_owned == serial.n_active_cells() &&
                n_different == 0 && n_not_found == 0,
              ExcMessage("the indexed triangulation differs from deal.II's"));
  return 0;
}
