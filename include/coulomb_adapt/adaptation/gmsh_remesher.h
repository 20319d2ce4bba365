#ifndef coulomb_adapt_adaptation_gmsh_remesher_h
#define coulomb_adapt_adaptation_gmsh_remesher_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** A triangle of the current mesh with the target element size h* at
   * its vertices: a piece of the size field handed to gmsh. */
  struct SizeFieldTriangle
  {
    std::array<Point<2>, 3> vertices;
    std::array<double, 3>   size;
  };

  /**
   * The size field h*(x) of a triangle mesh, on rank 0 (empty on the
   * others, which do not mesh): h*_E = r_E h_E
   * with h_E = (4 |E| / sqrt 3)^1/2, the edge of the equilateral triangle of
   * the same area (so that the cell count of the new mesh is sum_E r_E^-2
   * for any shape), smoothed by taking at each vertex the geometric mean of
   * h*_E over the cells around it, then scaled so that the smoothed,
   * piecewise linear field has the cell count sum_E r_E^-2 of the
   * unsmoothed one. @p ratio holds r_E per active cell (locally owned
   * entries).
   */
  std::vector<SizeFieldTriangle>
  nodal_size_field(const ElasticBody &body, const Vector<double> &ratio);

  /**
   * Mesh the domain of @p geometry (a body's coarse mesh: its boundary,
   * closed curves, the outer one and one per hole, give the geometry)
   * with gmsh's triangles of size
   * @p size_field (a PostView background field, linear in each triangle).
   * The boundary is rebuilt as gmsh curves: maximal runs of boundary faces
   * with the same boundary id and manifold id that are straight (flat
   * manifold) or lie on one SphericalManifold (circle arcs); boundary ids
   * and manifold ids are carried over. Rank 0 of @p comm meshes, every
   * rank receives the mesh. @p body_name is for messages; @p algorithm is
   * gmsh's 2D algorithm, "frontal-delaunay" or "delaunay".
   * @p interior_lines are straight segments through the body whose end
   * points are vertices of @p geometry's boundary (symmetry lines that
   * point constraints hold): the new mesh has a line of nodes on each.
   * @p support_points (point supports) are nodes of the new mesh: a curve
   * ends at those on the boundary, the others are embedded.
   */
  CoarseMeshData
  remesh_with_gmsh(const Triangulation<2>                     &geometry,
                   const std::vector<SizeFieldTriangle>       &size_field,
                   const std::string                          &body_name,
                   const MPI_Comm                              comm,
                   const std::string                          &algorithm,
                   const std::vector<std::array<Point<2>, 2>> &interior_lines,
                   const std::vector<Point<2>> &support_points = {});
} // namespace coulomb_adapt

#endif
