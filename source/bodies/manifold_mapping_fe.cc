#include <deal.II/grid/manifold.h>
#include <deal.II/grid/reference_cell.h>

#include <coulomb_adapt/bodies/manifold_mapping_fe.h>

#include <cmath>

namespace coulomb_adapt
{
  ManifoldMappingFE::ManifoldMappingFE(const FiniteElement<2, 2> &fe)
    : MappingFE<2>(fe)
  {
    AssertThrow(fe.reference_cell() == ReferenceCells::Triangle,
                ExcMessage("ManifoldMappingFE is for triangles"));
    // The reference triangle's lines run from vertex (0, 0) to (1, 0),
    // from (1, 0) to (0, 1) and from (0, 1) to (0, 0).
    const double tolerance = 1e-12;
    for (const Point<2> &p : fe.get_unit_support_points())
      {
        LinePosition position{numbers::invalid_unsigned_int, 0};
        const bool   vertex = (p.norm() < tolerance) ||
                            (p.distance(Point<2>(1, 0)) < tolerance) ||
                            (p.distance(Point<2>(0, 1)) < tolerance);
        if (!vertex)
          {
            if (std::abs(p[1]) < tolerance)
              position = {0, p[0]};
            else if (std::abs(p[0] + p[1] - 1) < tolerance)
              position = {1, p[1]};
            else if (std::abs(p[0]) < tolerance)
              position = {2, 1 - p[1]};
          }
        line_positions.push_back(position);
      }
  }



  std::unique_ptr<Mapping<2>>
  ManifoldMappingFE::clone() const
  {
    return std::make_unique<ManifoldMappingFE>(*fe);
  }



  std::vector<Point<2>>
  ManifoldMappingFE::compute_mapping_support_points(
    const Triangulation<2>::cell_iterator &cell) const
  {
    std::vector<Point<2>> points =
      MappingFE<2>::compute_mapping_support_points(cell);
    static constexpr unsigned int line_vertices[3][2] = {{0, 1},
                                                         {1, 2},
                                                         {2, 0}};
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        const LinePosition &position = line_positions[i];
        if (position.line == numbers::invalid_unsigned_int)
          continue;
        const auto line = cell->line(position.line);
        if (line->manifold_id() == numbers::flat_manifold_id)
          continue;
        points[i] = line->get_manifold().get_intermediate_point(
          cell->vertex(line_vertices[position.line][0]),
          cell->vertex(line_vertices[position.line][1]),
          position.fraction);
      }
    return points;
  }
} // namespace coulomb_adapt
