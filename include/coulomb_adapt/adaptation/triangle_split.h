#ifndef coulomb_adapt_adaptation_triangle_split_h
#define coulomb_adapt_adaptation_triangle_split_h

#include <deal.II/grid/tria.h>

#include <coulomb_adapt/adaptation/size_field.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * The cell count of a size field: the integral of 1 / (sqrt 3 / 4 h^2)
   * (the equilateral triangle of edge h) over its triangles, with h linear
   * in each (evaluated at the edge midpoints, as nodal_size_field()
   * scales it). What gmsh's mesh of the field has, to a few percent.
   */
  double
  size_field_cell_count(const std::vector<SizeFieldTriangle> &size_field);

  /**
   * How many times a body's gmsh mesh is split into 4 (split_triangles())
   * when its size field asks for @p n_cells cells: the smallest k with
   * n_cells / 4^k <= @p split_above_cells, so that gmsh meshes between a
   * quarter of that and that many cells; 0 if @p split_above_cells is 0
   * (never split) or n_cells is at most that.
   */
  unsigned int
  n_triangle_splits(const double n_cells, const unsigned int split_above_cells);

  /** Multiply every size of @p size_field by 2^@p n_splits: gmsh's mesh of
   * it split n_splits times has the field's sizes again. */
  void
  coarsen_size_field(std::vector<SizeFieldTriangle> &size_field,
                     const unsigned int              n_splits);

  /**
   * Red refinement of a triangle mesh, @p n_times: each triangle is split
   * into 4 at its edges' midpoints (the 3 corner triangles and the middle
   * one), each midpoint shared by the edge's two triangles. Every child is
   * similar to its parent, so the angles are those of @p mesh, and the
   * orientation (counter-clockwise) and material id are the parent's.
   * A boundary line becomes two with its boundary id and manifold id; the
   * midpoint of a line with a manifold id is put on @p geometry's manifold
   * of that id (the curve), the other midpoints are the straight ones.
   * The old vertices keep their numbers (support points and the ends of
   * interior lines stay vertices; an interior line, a chain of edges,
   * stays one), the midpoints follow; the children of a cell are
   * consecutive, in the order of the parents. Throws if a child on a
   * curved boundary turned over (a curve that bends more than the cells
   * along it can follow).
   */
  void
  split_triangles(CoarseMeshData         &mesh,
                  const Triangulation<2> &geometry,
                  const unsigned int      n_times);
} // namespace coulomb_adapt

#endif
