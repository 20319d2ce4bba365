#ifndef coulomb_adapt_bodies_triangle_mesh_description_h
#define coulomb_adapt_bodies_triangle_mesh_description_h

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria_description.h>

#include <coulomb_adapt/scenes/gmsh_reader.h>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * This rank's part of a triangle mesh (the remesher's CoarseMeshData, one
   * level) as the description a parallel::fullydistributed::Triangulation
   * is built from, without a serial Triangulation.
   *
   * It equals (Description::operator==) deal.II 9.4's
   * create_description_from_triangulation() of the serial mesh that
   * CoarseMeshData::create_triangulation() builds, partitioned by
   * GridTools::partition_triangulation() (METIS on the cells' face
   * graph): the cells a rank owns, every cell sharing a vertex with them,
   * the vertices of those cells in their global order, each face's
   * boundary id and each line's manifold id. Building the serial mesh for
   * this took about a third of the remeshing time of an adaptive run
   * (benchmarks/adaptive_run), and it held the whole mesh on every rank.
   *
   * Every cell must be a triangle; boundary lines name boundary faces (a
   * listed interior line keeps only its manifold id, as in deal.II).
   */
  TriangulationDescription::Description<2, 2>
  describe_triangle_mesh(const CoarseMeshData &mesh, const MPI_Comm comm);
} // namespace coulomb_adapt

#endif
