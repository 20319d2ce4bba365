#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/size_field.h>
#include <coulomb_adapt/core/gather_numbers.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    // A cell packed as numbers for the gather: its three vertices (x, y),
    // its target size h*_E and its area |E|.
    constexpr unsigned int n_values = 8;
    using PackedCell                = std::array<double, n_values>;
    using VertexKey                 = std::pair<double, double>;



    // The owned cells of @p body with h*_E = r_E h_E, gathered on rank
    // @p root, the one that meshes the body. The cells are put in a fixed order, whatever the
    // partition: gmsh's result depends on the order of the view's
    // triangles and on the last bits of the sizes, and the mesh must not
    // depend on the number of ranks. The sizes are rounded to float for the
    // same reason (r_E comes from MPI sums).
    std::vector<PackedCell>
    gathered_cells(const ElasticBody    &body,
                   const Vector<double> &ratio,
                   const unsigned int    root)
    {
      std::vector<double> local;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            AssertThrow(cell->n_vertices() == 3,
                        ExcMessage("the size field is built on triangles"));
            for (unsigned int v = 0; v < 3; ++v)
              {
                local.push_back(cell->vertex(v)[0]);
                local.push_back(cell->vertex(v)[1]);
              }
            const double h = std::sqrt(4 * cell->measure() / std::sqrt(3.));
            local.push_back(ratio(cell->active_cell_index()) * h);
            local.push_back(cell->measure());
          }
      const auto gathered =
        gather_numbers(body.dof_handler().get_communicator(), local, root);
      std::vector<PackedCell> cells;
      for (const auto &part : gathered)
        for (std::size_t c = 0; c < part.size(); c += n_values)
          {
            PackedCell cell;
            std::copy(part.begin() + c,
                      part.begin() + c + n_values,
                      cell.begin());
            cell[6] = static_cast<float>(cell[6]);
            cells.push_back(cell);
          }
      std::sort(cells.begin(), cells.end());
      return cells;
    }



    // The size at each corner of each cell (index 3 c + v): the geometric
    // mean of h*_E over the cells around its vertex, since sizes vary over
    // orders of magnitude. The corners are sorted by vertex, and by index
    // within a vertex, so that each vertex's logarithms are summed in the
    // cells' order; a sorted vector instead of a map (ordered by vertex),
    // which took about half of the size field's time on large meshes.
    std::vector<double>
    corner_sizes(const std::vector<PackedCell> &cells)
    {
      struct Corner
      {
        VertexKey   vertex;
        std::size_t index;
      };
      std::vector<Corner> corners;
      corners.reserve(3 * cells.size());
      for (std::size_t c = 0; c < cells.size(); ++c)
        for (unsigned int v = 0; v < 3; ++v)
          corners.push_back(
            {{cells[c][2 * v], cells[c][2 * v + 1]}, 3 * c + v});
      std::sort(corners.begin(),
                corners.end(),
                [](const Corner &x, const Corner &y) {
                  return std::tie(x.vertex, x.index) <
                         std::tie(y.vertex, y.index);
                });
      std::vector<double> sizes(corners.size());
      for (std::size_t first = 0; first < corners.size();)
        {
          std::size_t end     = first;
          double      log_sum = 0;
          for (; end < corners.size() &&
                 corners[end].vertex == corners[first].vertex;
               ++end)
            log_sum += std::log(cells[corners[end].index / 3][6]);
          const double size = std::exp(log_sum / (end - first));
          for (; first < end; ++first)
            sizes[corners[first].index] = size;
        }
      return sizes;
    }



    // Smoothing must not change the cell count the optimum asked for: the
    // count of a size field is int 1 / (sqrt 3 / 4 h(x)^2) dx, with h
    // constant per cell before and linear per cell after the smoothing
    // (integrated at the edge midpoints). Near a singular point the
    // smoothed field is much finer on average, so without this scaling the
    // new mesh has up to a third more cells than N*.
    void
    scale_to_cell_count(const std::vector<PackedCell>  &cells,
                        std::vector<SizeFieldTriangle> &field)
    {
      double n_wanted = 0, n_smoothed = 0;
      for (std::size_t c = 0; c < cells.size(); ++c)
        {
          const double area = cells[c][7];
          n_wanted += area / (cells[c][6] * cells[c][6]);
          for (unsigned int v = 0; v < 3; ++v)
            {
              const double h =
                0.5 * (field[c].size[v] + field[c].size[(v + 1) % 3]);
              n_smoothed += area / 3 / (h * h);
            }
        }
      const double scale = n_wanted > 0 ? std::sqrt(n_smoothed / n_wanted) : 1;
      for (auto &t : field)
        for (double &h : t.size)
          h = static_cast<float>(h * scale);
    }
  } // namespace



  std::vector<SizeFieldTriangle>
  nodal_size_field(const ElasticBody    &body,
                   const Vector<double> &ratio,
                   const unsigned int    root)
  {
    const auto                     cells = gathered_cells(body, ratio, root);
    const std::vector<double>      sizes = corner_sizes(cells);
    std::vector<SizeFieldTriangle> field(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (unsigned int v = 0; v < 3; ++v)
        {
          field[c].vertices[v] = Point<2>(cells[c][2 * v], cells[c][2 * v + 1]);
          field[c].size[v]     = sizes[3 * c + v];
        }
    scale_to_cell_count(cells, field);
    return field;
  }
} // namespace coulomb_adapt
