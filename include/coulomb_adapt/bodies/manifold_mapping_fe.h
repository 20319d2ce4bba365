#ifndef coulomb_adapt_bodies_manifold_mapping_fe_h
#define coulomb_adapt_bodies_manifold_mapping_fe_h

#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping_fe.h>

#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * MappingFE (triangles) whose support points on the edges of a cell lie
   * on the edge's manifold: deal.II 9.4's MappingFE interpolates them
   * between the vertices, so that with FE_SimplexP(2) a boundary edge on a
   * circle stays a chord. Here the middle node of a P2 edge with a
   * SphericalManifold is the manifold's midpoint, and the edge becomes the
   * parabola through the two vertices and that point. Edges on the flat
   * manifold and the cell's interior points are as MappingFE puts them.
   */
  class ManifoldMappingFE : public MappingFE<2>
  {
  public:
    explicit ManifoldMappingFE(const FiniteElement<2, 2> &fe);

    std::unique_ptr<Mapping<2>>
    clone() const override;

  protected:
    std::vector<Point<2>>
    compute_mapping_support_points(
      const Triangulation<2>::cell_iterator &cell) const override;

  private:
    /** Per support point of the mapping's element: the cell's line it lies
     * on and its fraction along that line from the line's first vertex
     * (in the reference triangle's numbering), or an invalid line for the
     * vertices and interior points. */
    struct LinePosition
    {
      unsigned int line;
      double       fraction;
    };
    std::vector<LinePosition> line_positions;
  };
} // namespace coulomb_adapt

#endif
