#ifndef coulomb_adapt_scenes_scene_meshes_h
#define coulomb_adapt_scenes_scene_meshes_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <coulomb_adapt/core/parameters.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Boundary ids shared by the built-in scenes (the gmsh scene maps its
   * physical groups onto the same ids).
   */
  namespace boundary_ids
  {
    constexpr types::boundary_id traction_free = 0;
    constexpr types::boundary_id contact       = 1;
    constexpr types::boundary_id dirichlet     = 2;
    constexpr types::boundary_id traction      = 3;
    constexpr types::boundary_id roller        = 4;
  } // namespace boundary_ids

  /**
   * Fill @p tria with the rectangle [p1, p2] divided into
   * @p subdivisions[0] x @p subdivisions[1] quadrilaterals, or the same
   * mesh with each quadrilateral split into triangles. @p side_ids are the
   * boundary ids of the left, right, bottom and top sides.
   */
  void
  make_rectangle(Triangulation<2>                        &tria,
                 const Point<2>                          &p1,
                 const Point<2>                          &p2,
                 const std::vector<unsigned int>         &subdivisions,
                 const std::array<types::boundary_id, 4> &side_ids,
                 const CellType                           cell_type);

  /**
   * Read "nx, ny" from entry @p entry of the current subsection: two
   * positive integers, or a ParameterError naming @p path.
   */
  std::vector<unsigned int>
  get_subdivisions(ParameterHandler  &prm,
                   const std::string &entry,
                   const std::string &path);

  /**
   * Refine the cells of @p tria closer than @p radius + (cell diameter) to
   * @p point until their edges are no longer than @p target_size: a mesh
   * graded towards a contact point.
   */
  void
  refine_towards_point(Triangulation<2> &tria,
                       const Point<2>   &point,
                       const double      radius,
                       const double      target_size);
} // namespace coulomb_adapt

#endif
