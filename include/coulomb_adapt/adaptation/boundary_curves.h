#ifndef coulomb_adapt_adaptation_boundary_curves_h
#define coulomb_adapt_adaptation_boundary_curves_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <array>
#include <set>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * A body's coarse mesh seen as the geometry to remesh: its boundary as
   * curves, and the points and lines inside it that the new mesh keeps.
   * Nothing here calls gmsh; gmsh_remesher.cc turns these into gmsh's
   * geometry.
   */
  namespace boundary_geometry
  {
    /** One gmsh curve: a run of boundary vertices with one boundary id and
     * one manifold id. */
    struct Curve
    {
      std::vector<unsigned int> vertices;
      types::boundary_id        boundary_id;
      types::manifold_id        manifold_id;
    };

    /** What the new mesh keeps of the points and lines inside the body:
     * the boundary vertices where interior lines end (@p line_ends, also
     * in @p corners), the point supports on the boundary (in @p corners,
     * where a curve must end) and those inside (@p embedded_points). */
    struct InteriorFeatures
    {
      std::vector<std::array<unsigned int, 2>> line_ends;
      std::set<unsigned int>                   corners;
      std::vector<Point<2>>                    embedded_points;
    };

    /** The features of @p interior_lines (straight segments whose ends are
     * boundary vertices of @p geometry) and @p support_points; either way a
     * support stays a node. @p body_name is for messages. */
    InteriorFeatures
    interior_features(
      const Triangulation<2>                     &geometry,
      const std::string                          &body_name,
      const std::vector<std::array<Point<2>, 2>> &interior_lines,
      const std::vector<Point<2>>                &support_points);

    /** The curves of all boundary loops, loop by loop, and the loops
     * grouped into the body's connected parts: each part is an outer loop
     * followed by the loops of its holes. A loop inside an even number of
     * other loops is an outer loop (a body may have several parts, and a
     * part may sit in another part's hole); a loop inside an odd number is
     * a hole of the innermost loop around it. */
    struct LoopCurves
    {
      std::vector<Curve> curves;
      /** The first curve of each loop, and curves.size() last. */
      std::vector<unsigned int> first_curve_of_loop;
      /** Per part: its outer loop, then its holes. */
      std::vector<std::vector<unsigned int>> parts;
      /** Each loop's vertices in the order of its walk. */
      std::vector<std::vector<Point<2>>> loop_polygons;

      unsigned int
      n_loops() const;

      unsigned int
      loop_of_curve(const unsigned int c) const;

      /** The part whose region (inside its outer loop, outside its holes)
       * holds @p x, or numbers::invalid_unsigned_int. */
      unsigned int
      part_containing(const Point<2> &x) const;
    };

    /** The boundary of @p geometry as curves: maximal runs of boundary
     * faces with the same boundary id and manifold id that are straight
     * (flat manifold) or lie on one manifold, ending also at @p corners. */
    LoopCurves
    loop_curves(const Triangulation<2>       &geometry,
                const std::string            &body_name,
                const std::set<unsigned int> &corners);
    /** Each vertex of @p mesh inside a run of boundary lines on a
     * CurveManifold of @p geometry moved onto that curve (gmsh's nodes
     * lie on its spline through points of the curve, not on the curve). */
    void
    put_nodes_on_curves(const Triangulation<2> &geometry, CoarseMeshData &mesh);
  } // namespace boundary_geometry
} // namespace coulomb_adapt

#endif
