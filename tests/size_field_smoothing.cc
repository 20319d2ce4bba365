// The remesher's size field (adaptation/size_field.h), against what its
// documentation promises, computed here from the mesh independently:
//  - one triangle per cell of the body, on the gathering rank;
//  - at a vertex, every cell around it gives the same size (the field is
//    continuous);
//  - the sizes are the geometric means of h*_E = r_E (4 |E| / sqrt 3)^1/2
//    over the cells around each vertex, times one factor for the whole
//    body: size / mean is the same at every vertex (to the float rounding
//    of the sizes);
//  - that factor keeps the cell count: sum_E |E| / h*_E^2 equals the
//    smoothed field's count, sum_E |E| / 3 sum_edges 1 / h(midpoint)^2.
// On the blocks' triangles (both bodies, one global refinement) with r_E
// varying over an order of magnitude. 1 and 2 ranks print the same: the
// field does not depend on the partition.

#include <coulomb_adapt/adaptation/size_field.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <map>

using namespace coulomb_adapt;

namespace
{
  using VertexKey = std::pair<double, double>;

  // r_E from the cell's centre: 0.1 ... 1.9, smooth, the same on every
  // rank for owned and ghost cells.
  double
  ratio_at(const Point<2> &x)
  {
    return 1. + 0.9 * std::sin(0.05 * x[0]) * std::cos(0.07 * x[1]);
  }

  void
  check_body(const Scene &scene, const unsigned int b, const Parameters &p)
  {
    auto        out = testing::root_output();
    ElasticBody body(
      MPI_COMM_WORLD, scene, b, p.mesh.cell_type, 1, p.finite_elements);
    const auto    &tria = body.triangulation();
    Vector<double> ratio(tria.n_active_cells());
    for (const auto &cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        ratio(cell->active_cell_index()) = ratio_at(cell->center());

    // Per vertex of an owned cell: the mean of log h*_E over all cells
    // around it (owned or ghost: the ghost layer holds every cell that
    // shares a vertex with an owned one).
    std::map<VertexKey, std::pair<double, unsigned int>> log_sums;
    for (const auto &cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const double h_star = ratio(cell->active_cell_index()) *
                                std::sqrt(4 * cell->measure() / std::sqrt(3.));
          for (unsigned int v = 0; v < 3; ++v)
            {
              auto &entry = log_sums[{cell->vertex(v)[0], cell->vertex(v)[1]}];
              entry.first += std::log(h_star);
              ++entry.second;
            }
        }
    std::vector<std::array<double, 3>> owned_means;
    double                             wanted_count = 0;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double h_star = ratio(cell->active_cell_index()) *
                                std::sqrt(4 * cell->measure() / std::sqrt(3.));
          wanted_count += cell->measure() / (h_star * h_star);
          for (unsigned int v = 0; v < 3; ++v)
            {
              const auto &e =
                log_sums.at({cell->vertex(v)[0], cell->vertex(v)[1]});
              owned_means.push_back({{cell->vertex(v)[0],
                                      cell->vertex(v)[1],
                                      std::exp(e.first / e.second)}});
            }
        }
    wanted_count = Utilities::MPI::sum(wanted_count, MPI_COMM_WORLD);
    const auto gathered_means =
      Utilities::MPI::gather(MPI_COMM_WORLD, owned_means, 0);

    const std::vector<SizeFieldTriangle> field =
      nodal_size_field(body, ratio, 0);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      {
        AssertThrow(field.empty(), ExcMessage("a field off the root rank"));
        return;
      }

    std::map<VertexKey, double> mean_at;
    for (const auto &part : gathered_means)
      for (const auto &[x, y, mean] : part)
        mean_at[{x, y}] = mean;

    std::map<VertexKey, double> size_at;
    double                      smallest_factor = 1e300, largest_factor = 0;
    double       smoothed_count = 0, smallest = 1e300, largest = 0;
    unsigned int n_discontinuous = 0;
    for (const auto &t : field)
      {
        for (unsigned int v = 0; v < 3; ++v)
          {
            const Point<2> &a            = t.vertices[v];
            const VertexKey key          = {a[0], a[1]};
            const auto [entry, inserted] = size_at.emplace(key, t.size[v]);
            if (!inserted && entry->second != t.size[v])
              ++n_discontinuous;
            const double factor = t.size[v] / mean_at.at(key);
            smallest_factor     = std::min(smallest_factor, factor);
            largest_factor      = std::max(largest_factor, factor);
            smallest            = std::min(smallest, t.size[v]);
            largest             = std::max(largest, t.size[v]);
          }
      }
    // The smoothed field's count: h linear on each triangle, integrated
    // at the edges' midpoints.
    for (const auto &t : field)
      {
        double area = 0;
        for (unsigned int v = 0; v < 3; ++v)
          {
            const Point<2> &a = t.vertices[v], &c = t.vertices[(v + 1) % 3];
            area += 0.5 * (a[0] * c[1] - c[0] * a[1]);
          }
        for (unsigned int v = 0; v < 3; ++v)
          {
            const double h_mid = 0.5 * (t.size[v] + t.size[(v + 1) % 3]);
            smoothed_count += std::abs(area) / 3 / (h_mid * h_mid);
          }
      }

    const double factor_spread = largest_factor / smallest_factor - 1;
    const double count_defect =
      std::abs(smoothed_count - wanted_count) / wanted_count;
    out << "body " << b + 1 << ": " << field.size() << " triangles ("
        << tria.n_global_active_cells() << " cells), sizes "
        << std::setprecision(4) << smallest << " ... " << largest
        << " mm, one size per vertex: " << (n_discontinuous == 0 ? "yes" : "no")
        << ", size / geometric mean the same at every vertex (factor "
        << smallest_factor << "): " << (factor_spread < 1e-6 ? "yes" : "no")
        << ", cell count kept (" << wanted_count
        << "): " << (count_defect < 1e-6 ? "yes" : "no") << std::endl;
    AssertThrow(field.size() == tria.n_global_active_cells(),
                ExcMessage("not one triangle per cell"));
    AssertThrow(size_at.size() == mean_at.size(),
                ExcMessage("the field's vertices are not the mesh's"));
    AssertThrow(n_discontinuous == 0,
                ExcMessage(std::to_string(n_discontinuous) +
                           " corners differ from their vertex's size"));
    AssertThrow(factor_spread < 1e-6,
                ExcMessage("size / geometric mean varies by " +
                           std::to_string(factor_spread)));
    AssertThrow(count_defect < 1e-6,
                ExcMessage("cell count changed by " +
                           std::to_string(count_defect)));
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  const Parameters                 parameters = testing::make_parameters(
    prm, {{"Scene/Name", "blocks"}, {"Mesh/Cell type", "triangle"}});
  const auto scene = scenes::create_scene(parameters, prm);
  for (unsigned int b = 0; b < 2; ++b)
    check_body(*scene, b, parameters);
}
