#include <coulomb_adapt/adaptation/triangle_split.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

// gmsh's frontal Delaunay costs about 20 us per triangle
// (benchmarks/adaptive_run/README.md), red refinement a small fraction of
// that: a large body is meshed by gmsh at 2^k times the planned size and
// split k times. The size grading is resolved on the coarser mesh only;
// the shapes are gmsh's.
namespace coulomb_adapt
{
  double
  size_field_cell_count(const std::vector<SizeFieldTriangle> &size_field)
  {
    double n_cells = 0;
    for (const auto &t : size_field)
      {
        const Tensor<1, 2> u = t.vertices[1] - t.vertices[0],
                           v = t.vertices[2] - t.vertices[0];
        const double area    = 0.5 * std::abs(u[0] * v[1] - u[1] * v[0]);
        for (unsigned int e = 0; e < 3; ++e)
          {
            const double h = 0.5 * (t.size[e] + t.size[(e + 1) % 3]);
            n_cells += area / 3 / (std::sqrt(3.) / 4 * h * h);
          }
      }
    return n_cells;
  }



  unsigned int
  n_triangle_splits(const double n_cells, const unsigned int split_above_cells)
  {
    unsigned int k = 0;
    if (split_above_cells > 0)
      while (n_cells / std::pow(4., k) > split_above_cells)
        ++k;
    return k;
  }



  void
  coarsen_size_field(std::vector<SizeFieldTriangle> &size_field,
                     const unsigned int              n_splits)
  {
    const double factor = std::pow(2., n_splits);
    for (auto &t : size_field)
      for (double &h : t.size)
        h *= factor;
  }



  namespace
  {
    std::uint64_t
    edge_key(const unsigned int a, const unsigned int b)
    {
      return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    }



    double
    signed_area(const std::vector<Point<2>> &vertices, const CellData<2> &cell)
    {
      const Tensor<1, 2> u = vertices[cell.vertices[1]] -
                             vertices[cell.vertices[0]],
                         v = vertices[cell.vertices[2]] -
                             vertices[cell.vertices[0]];
      return 0.5 * (u[0] * v[1] - u[1] * v[0]);
    }



    // One red refinement of @p mesh.
    void
    split_once(CoarseMeshData &mesh, const Triangulation<2> &geometry)
    {
      auto &vertices = mesh.vertices;
      auto &lines    = mesh.boundary_lines.boundary_lines;
      // Each edge's midpoint, numbered after the old vertices: first those
      // of the boundary lines (on their curve), then the cells' others in
      // the order of the cells.
      std::unordered_map<std::uint64_t, unsigned int> midpoint;
      midpoint.reserve(3 * mesh.cells.size() / 2 + lines.size());
      const auto add_midpoint = [&](const unsigned int       a,
                                    const unsigned int       b,
                                    const types::manifold_id manifold_id) {
        const auto [it, added] =
          midpoint.emplace(edge_key(a, b), vertices.size());
        if (added)
          {
            const std::array<Point<2>, 2> ends = {{vertices[a], vertices[b]}};
            vertices.push_back(
              manifold_id == numbers::flat_manifold_id ?
                Point<2>(0.5 * (ends[0] + ends[1])) :
                geometry.get_manifold(manifold_id)
                  .get_intermediate_point(ends[0], ends[1], 0.5));
          }
        return it->second;
      };

      std::vector<CellData<1>> new_lines;
      new_lines.reserve(2 * lines.size());
      for (const auto &line : lines)
        {
          const unsigned int m =
            add_midpoint(line.vertices[0], line.vertices[1], line.manifold_id);
          for (const auto &ends :
               {std::array<unsigned int, 2>{{line.vertices[0], m}},
                std::array<unsigned int, 2>{{m, line.vertices[1]}}})
            {
              CellData<1> child = line;
              child.vertices    = {ends[0], ends[1]};
              new_lines.push_back(child);
            }
        }
      lines = std::move(new_lines);

      std::vector<CellData<2>> new_cells;
      new_cells.reserve(4 * mesh.cells.size());
      for (const auto &cell : mesh.cells)
        {
          const auto        &v = cell.vertices;
          const unsigned int m01 =
            add_midpoint(v[0], v[1], numbers::flat_manifold_id);
          const unsigned int m12 =
            add_midpoint(v[1], v[2], numbers::flat_manifold_id);
          const unsigned int m20 =
            add_midpoint(v[2], v[0], numbers::flat_manifold_id);
          // The corner triangles, then the middle one (its vertices in the
          // parent's sense of rotation).
          for (const auto &corners :
               {std::array<unsigned int, 3>{{v[0], m01, m20}},
                std::array<unsigned int, 3>{{m01, v[1], m12}},
                std::array<unsigned int, 3>{{m20, m12, v[2]}},
                std::array<unsigned int, 3>{{m01, m12, m20}}})
            {
              CellData<2> child(3);
              child.vertices    = {corners[0], corners[1], corners[2]};
              child.material_id = cell.material_id;
              child.manifold_id = cell.manifold_id;
              AssertThrow(signed_area(vertices, child) > 0,
                          ExcMessage(
                            "splitting gmsh's triangles: a triangle at (" +
                            std::to_string(vertices[corners[0]][0]) + ", " +
                            std::to_string(vertices[corners[0]][1]) +
                            ") turned over when its boundary edge's "
                            "midpoint was put on the curve"));
              new_cells.push_back(child);
            }
        }
      mesh.cells = std::move(new_cells);
    }
  } // namespace



  void
  split_triangles(CoarseMeshData         &mesh,
                  const Triangulation<2> &geometry,
                  const unsigned int      n_times)
  {
    for (unsigned int k = 0; k < n_times; ++k)
      split_once(mesh, geometry);
  }
} // namespace coulomb_adapt
