#ifndef coulomb_adapt_adaptation_gmsh_remesher_h
#define coulomb_adapt_adaptation_gmsh_remesher_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <coulomb_adapt/adaptation/size_field.h>
#include <coulomb_adapt/core/options.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Mesh the domain of @p geometry (a body's coarse mesh: its boundary,
   * closed curves, the outer one and one per hole of each connected part,
   * give the geometry; a body may be made of several parts)
   * with gmsh's triangles of size
   * @p size_field (a PostView background field, linear in each triangle).
   * The boundary is rebuilt as gmsh curves: maximal runs of boundary faces
   * with the same boundary id and manifold id that are straight (flat
   * manifold) or lie on one SphericalManifold (circle arcs) or on one
   * CurveManifold (a sampled spline of the scene: gmsh splines through
   * points of it, the new boundary nodes then moved onto it); boundary ids
   * and manifold ids are carried over. Rank 0 of @p comm meshes, every
   * rank receives the mesh. @p body_name is for messages; @p algorithm is
   * gmsh's 2D algorithm.
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
                   const RemeshingAlgorithm                    algorithm,
                   const std::vector<std::array<Point<2>, 2>> &interior_lines,
                   const std::vector<Point<2>> &support_points = {});



  /**
   * What gmsh made of one body on the process that meshed it: the mesh
   * packed for the broadcast, or gmsh's error. Empty on the other ranks.
   */
  struct GmshMeshing
  {
    std::vector<double> packed_mesh;
    std::string         error;
  };

  /**
   * remesh_with_gmsh() in two halves, so that the bodies can be meshed at
   * the same time on different ranks: mesh_with_gmsh_here() runs gmsh on
   * the calling process only (its own gmsh::initialize() and finalize();
   * not collective, no MPI call), with the arguments of
   * remesh_with_gmsh(), and splits gmsh's mesh @p n_splits times into 4
   * (split_triangles(), before it is packed: the caller has scaled
   * @p size_field by 2^n_splits); share_gmsh_mesh() is collective over
   * @p comm and
   * gives every rank the mesh made on rank @p root, or throws gmsh's error
   * on every rank.
   */
  GmshMeshing
  mesh_with_gmsh_here(
    const Triangulation<2>                     &geometry,
    const std::vector<SizeFieldTriangle>       &size_field,
    const std::string                          &body_name,
    const RemeshingAlgorithm                    algorithm,
    const std::vector<std::array<Point<2>, 2>> &interior_lines,
    const std::vector<Point<2>>                &support_points = {},
    const unsigned int                          n_splits       = 0);

  CoarseMeshData
  share_gmsh_mesh(const GmshMeshing &meshing,
                  const std::string &body_name,
                  const MPI_Comm     comm,
                  const unsigned int root);
} // namespace coulomb_adapt

#endif
