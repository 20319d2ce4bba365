// describe_triangle_mesh (bodies/triangle_mesh_description.h) builds the
// description of a fully distributed triangulation straight from a
// triangle mesh; it must equal deal.II's
// create_description_from_triangulation() of the serial mesh partitioned
// by GridTools::partition_triangulation(), on every rank.
//
// The mesh: 2 x 30 x 20 triangles on [0, 3] x [0, 2], its vertices
// numbered in a shuffled order, its cells shuffled and each one's vertices
// rotated (the orientation kept); boundary lines with ids 0 to 3 on the
// four sides, a manifold id on the top side's lines (listed in reverse
// vertex order), an interior line listed with a manifold id only, and
// the left side's lines not listed (boundary id 0). The fully distributed
// triangulations built from both descriptions must have the same cells.
// Counts are sums over the ranks: 1 and 2 ranks print the same.

#include <deal.II/distributed/fully_distributed_tria.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <coulomb_adapt/bodies/triangle_mesh_description.h>

#include "test_utilities.h"

#include <algorithm>
#include <numeric>
#include <random>

using namespace coulomb_adapt;

namespace
{
  CoarseMeshData
  shuffled_mesh()
  {
    Triangulation<2> generated;
    GridGenerator::subdivided_hyper_rectangle_with_simplices(generated,
                                                             {30, 20},
                                                             Point<2>(0, 0),
                                                             Point<2>(3, 2));
    std::mt19937              random(7);
    std::vector<unsigned int> new_index(generated.n_vertices());
    std::iota(new_index.begin(), new_index.end(), 0);
    std::shuffle(new_index.begin(), new_index.end(), random);

    CoarseMeshData mesh;
    mesh.vertices.resize(generated.n_vertices());
    for (unsigned int v = 0; v < generated.n_vertices(); ++v)
      mesh.vertices[new_index[v]] = generated.get_vertices()[v];
    for (const auto &cell : generated.active_cell_iterators())
      {
        CellData<2>        data(3);
        const unsigned int shift = cell->active_cell_index() % 3;
        for (unsigned int v = 0; v < 3; ++v)
          data.vertices[v] = new_index[cell->vertex_index((v + shift) % 3)];
        data.material_id = 4;
        mesh.cells.push_back(data);

        for (const unsigned int f : cell->face_indices())
          {
            const auto     face = cell->face(f);
            const Point<2> c    = face->center();
            CellData<1>    line;
            line.vertices = {new_index[face->vertex_index(0)],
                             new_index[face->vertex_index(1)]};
            if (face->at_boundary())
              {
                if (c[0] < 1e-12)
                  continue;
                line.boundary_id = c[0] > 3 - 1e-12 ? 1 : c[1] < 1e-12 ? 2 : 3;
                if (line.boundary_id == 3)
                  {
                    line.manifold_id = 7;
                    std::swap(line.vertices[0], line.vertices[1]);
                  }
              }
            else if (std::abs(c[1] - 1) < 1e-12 && c[0] < 1 &&
                     face->vertex(0)[1] == face->vertex(1)[1] &&
                     cell->center()[1] < 1)
              {
                line.boundary_id = numbers::internal_face_boundary_id;
                line.manifold_id = 5;
              }
            else
              continue;
            mesh.boundary_lines.boundary_lines.push_back(line);
          }
      }
    std::shuffle(mesh.cells.begin(), mesh.cells.end(), random);
    return mesh;
  }



  // deal.II leaves the fourth (quadrilateral) line id of a triangle's
  // description uninitialised.
  void
  normalise(TriangulationDescription::Description<2, 2> &description)
  {
    for (auto &level : description.cell_infos)
      for (auto &info : level)
        info.manifold_line_ids[3] = numbers::flat_manifold_id;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  const CoarseMeshData mesh = shuffled_mesh();
  out << "mesh: " << mesh.cells.size() << " triangles, "
      << mesh.boundary_lines.boundary_lines.size() << " listed lines"
      << std::endl;

  Triangulation<2> serial;
  mesh.create_triangulation(serial);
  GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(comm),
                                     serial);
  auto expected =
    TriangulationDescription::Utilities::create_description_from_triangulation(
      serial, comm);
  normalise(expected);
  auto direct = describe_triangle_mesh(mesh, comm);
  normalise(direct);

  const bool same = direct == expected;
  out << "descriptions equal on every rank: "
      << (Utilities::MPI::min(same ? 1 : 0, comm) == 1 ? "yes" : "no")
      << std::endl;
  AssertThrow(same, ExcMessage("the descriptions differ"));

  unsigned int n_boundary_faces = 0, n_manifold_lines = 0;
  for (const auto &info : direct.cell_infos[0])
    if (info.subdomain_id == Utilities::MPI::this_mpi_process(comm))
      {
        n_boundary_faces += info.boundary_ids.size();
        for (unsigned int l = 0; l < 3; ++l)
          n_manifold_lines +=
            info.manifold_line_ids[l] != numbers::flat_manifold_id;
      }
  out << "owned cells, all ranks: "
      << Utilities::MPI::sum<unsigned int>(
           std::count_if(direct.cell_infos[0].begin(),
                         direct.cell_infos[0].end(),
                         [&](const auto &info) {
                           return info.subdomain_id ==
                                  Utilities::MPI::this_mpi_process(comm);
                         }),
           comm)
      << std::endl
      << "boundary faces of owned cells, all ranks: "
      << Utilities::MPI::sum(n_boundary_faces, comm) << std::endl
      << "lines with a manifold id on owned cells, all ranks: "
      << Utilities::MPI::sum(n_manifold_lines, comm) << std::endl;

  parallel::fullydistributed::Triangulation<2> tria(comm);
  tria.create_triangulation(direct);
  out << "fully distributed mesh: " << tria.n_global_active_cells() << " cells"
      << std::endl;
}
