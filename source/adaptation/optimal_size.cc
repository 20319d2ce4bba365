#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/optimal_size.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace coulomb_adapt
{
  namespace
  {
    constexpr double dimension = 2;

    // The ends of the active part of the slave's contact boundary, along
    // the tangent of its first active node (the same on every rank: the
    // states are).
    void
    add_contact_zone_ends(const std::vector<ContactNodeState> &states,
                          std::set<std::pair<double, double>> &points)
    {
      const ContactNodeState *first = nullptr;
      double                  s_min = 0, s_max = 0;
      Point<2>                p_min, p_max;
      for (const auto &state : states)
        if (state.status != ContactStatus::open && state.facing_master)
          {
            if (first == nullptr)
              {
                first = &state;
                p_min = p_max = state.position;
                continue;
              }
            const double s =
              (state.position - first->position) * first->tangent;
            if (s < s_min)
              s_min = s, p_min = state.position;
            if (s > s_max)
              s_max = s, p_max = state.position;
          }
      if (first != nullptr)
        {
          points.emplace(p_min[0], p_min[1]);
          points.emplace(p_max[0], p_max[1]);
        }
    }



    // Boundary vertices where one of the body's singular parts (its scene
    // says which: by default the contact part and the clamped parts) meets
    // a part with another boundary id: the classical corner singularities
    // of elasticity with mixed boundary conditions. Only owned cells are
    // looked at (a ghost cell's face towards an absent cell also reports
    // at_boundary), so the ids of a vertex are combined over the ranks.
    void
    add_boundary_condition_changes(const ElasticBody                   &body,
                                   std::set<std::pair<double, double>> &points)
    {
      std::vector<std::array<double, 3>> local;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              for (unsigned int v = 0; v < face->n_vertices(); ++v)
                local.push_back({{face->vertex(v)[0],
                                  face->vertex(v)[1],
                                  double(face->boundary_id())}});
      std::map<std::pair<double, double>, std::set<types::boundary_id>> ids;
      for (const auto &part :
           Utilities::MPI::all_gather(body.dof_handler().get_communicator(),
                                      local))
        for (const auto &[x, y, id] : part)
          ids[{x, y}].insert(static_cast<types::boundary_id>(id));
      const std::vector<types::boundary_id> singular_parts =
        body.description().singular_parts();
      for (const auto &[point, point_ids] : ids)
        if (point_ids.size() > 1 &&
            std::any_of(singular_parts.begin(),
                        singular_parts.end(),
                        [&](const types::boundary_id id) {
                          return point_ids.count(id) > 0;
                        }))
          points.insert(point);
    }



    // Whether @p p is in @p cell or closer to it than @p reach, with
    // @p box the cell's bounding box (near_singular_point's test; the box
    // and the reach computed once per cell, not once per point).
    bool
    near_point(const Triangulation<2>::active_cell_iterator &cell,
               const BoundingBox<2>                         &box,
               const double                                  reach,
               const Point<2>                               &p)
    {
      if (box.point_inside(p, 1e-10))
        return true;
      double box_distance_squared = 0;
      for (unsigned int d = 0; d < 2; ++d)
        box_distance_squared += std::pow(
          std::max({0., box.lower_bound(d) - p[d], p[d] - box.upper_bound(d)}),
          2);
      if (box_distance_squared >= reach * reach)
        return false;
      // Outside the box, so outside the cell: the distance to the cell is
      // that to its nearest face (straight between its vertices).
      for (const auto &face : cell->face_iterators())
        {
          const Tensor<1, 2> edge = face->vertex(1) - face->vertex(0);
          const double       t =
            std::clamp(((p - face->vertex(0)) * edge) / edge.norm_square(),
                       0.,
                       1.);
          if ((p - (face->vertex(0) + t * edge)).norm() < reach)
            return true;
        }
      return false;
    }



    // The error model of theory.md section 4 over the cells: r_E for the
    // multiplier exp(L), and the error and cell count it predicts (sums
    // over all ranks).
    //
    // r_E is bounded above, and below if lower_bound. The multiplier is
    // found without the lower bound: cells that want to shrink more than
    // min_ratio allows are capped afterwards (the next cycle refines them
    // again) rather than compensated by refining every other cell more,
    // which overshot the cell count of the first cycle several times over.
    //
    // The lower bound is r_E >= min_ratio where q_E = p, and
    // min_ratio^{3/2} at singular points, where the error falls more
    // slowly with h. With min_ratio there too, the singular cells, which
    // hold most of the error of a coarse mesh, could reduce it by only
    // min_ratio^{1/2} per cycle, and a small epsilon_0 would take three or
    // four cycles for them alone. Bounding the error reduction instead
    // (r_E^{q_E} >= min_ratio^p, so min_ratio^2 for q = 1/2) lets the
    // asymptotic model plan from a coarse mesh far beyond where it holds,
    // and it over-refines the corners. benchmarks/adaptive_run measures
    // the choice: at most two steps, final meshes somewhat larger than
    // those of the slower loop.
    class SizeRatioModel
    {
    public:
      SizeRatioModel(const std::vector<OptimalSizePlanner::Cell> &cells,
                     const MPI_Comm                               comm,
                     const unsigned int                           degree,
                     const double                                 min_ratio,
                     const double                                 max_ratio)
        : comm(comm)
        , log_max_ratio(std::log(max_ratio))
      {
        // The bisections evaluate the model some 50 times per plan: per
        // cell one exp() per evaluation, from these logarithms. The lower
        // bound takes one of two values (regular, singular cell).
        const std::array<double, 2> log_lowest_ratio = {
          {std::log(lowest_size_ratio(min_ratio, false)),
           std::log(lowest_size_ratio(min_ratio, true))}};
        terms.reserve(cells.size());
        for (const auto &c : cells)
          terms.push_back(
            {c.epsilon_squared > 0 ?
               std::log(dimension / (2 * c.rate * c.epsilon_squared)) :
               0.,
             1 / (2 * c.rate + dimension),
             2 * c.rate,
             c.epsilon_squared > 0 ? std::log(c.epsilon_squared) : 0.,
             log_lowest_ratio[c.rate < degree],
             c.epsilon_squared > 0});
      }

      double
      ratio(const std::size_t cell, const double L) const
      {
        return std::exp(log_ratio(terms[cell], L, true));
      }

      // Decreases as L grows.
      double
      predicted_error_squared(const double L, const bool lower_bound) const
      {
        double sum = 0;
        for (const auto &t : terms)
          if (t.has_error)
            sum += std::exp(t.error_exponent * log_ratio(t, L, lower_bound) +
                            t.log_epsilon_squared);
        return Utilities::MPI::sum(sum, comm);
      }

      // Grows with L, as the error falls.
      double
      predicted_n_cells(const double L) const
      {
        double sum = 0;
        for (const auto &t : terms)
          sum += std::exp(-dimension * log_ratio(t, L, true));
        return Utilities::MPI::sum(sum, comm);
      }

    private:
      // log r_E = (log(d / (2 q_E epsilon_E^2)) - L) / (2 q_E + d), the
      // Lagrange condition, and its bounds.
      struct Terms
      {
        // error_exponent = 2 q_E: the predicted error is r_E^{2 q_E}
        // epsilon_E^2.
        double log_optimum_scale, inverse_exponent, error_exponent,
          log_epsilon_squared, log_lowest_ratio;
        bool has_error;
      };

      double
      log_ratio(const Terms &t, const double L, const bool lower_bound) const
      {
        if (!t.has_error)
          return log_max_ratio;
        const double log_r =
          std::clamp((t.log_optimum_scale - L) * t.inverse_exponent,
                     -300.,
                     300.);
        return std::min(lower_bound ? std::max(log_r, t.log_lowest_ratio) :
                                      log_r,
                        log_max_ratio);
      }

      const MPI_Comm     comm;
      const double       log_max_ratio;
      std::vector<Terms> terms;
    };



    // The multiplier of the target error: bisect on L.
    double
    multiplier_for_error(const SizeRatioModel &model, const double target_error)
    {
      const double target2 = target_error * target_error;
      double       L_low = -1400, L_high = 1400;
      for (unsigned int k = 0; k < 200 && L_high - L_low > 1e-12; ++k)
        {
          const double L = 0.5 * (L_low + L_high);
          if (model.predicted_error_squared(L, false) > target2)
            L_low = L;
          else
            L_high = L;
        }
      return L_high;
    }



    // The multiplier of the smallest mesh of at least @p min_n_cells cells,
    // above @p L (bisection; the cell count grows with L).
    double
    multiplier_for_min_cell_count(const SizeRatioModel &model,
                                  double                L,
                                  const double          min_n_cells)
    {
      double L_more = 1400;
      for (unsigned int k = 0; k < 200 && L_more - L > 1e-12; ++k)
        {
          const double L_middle = 0.5 * (L + L_more);
          if (model.predicted_n_cells(L_middle) < min_n_cells)
            L = L_middle;
          else
            L_more = L_middle;
        }
      return L_more;
    }



    // The multiplier of the largest mesh of at most @p max_n_cells cells,
    // below @p L (bisection).
    double
    multiplier_for_cell_count(const SizeRatioModel &model,
                              double                L,
                              const double          max_n_cells)
    {
      double L_fewer = -1400;
      for (unsigned int k = 0; k < 200 && L - L_fewer > 1e-12; ++k)
        {
          const double L_middle = 0.5 * (L_fewer + L);
          if (model.predicted_n_cells(L_middle) > max_n_cells)
            L = L_middle;
          else
            L_fewer = L_middle;
        }
      return L_fewer;
    }
  } // namespace



  bool
  near_singular_point(const Triangulation<2>::active_cell_iterator &cell,
                      const Point<2>                               &p)
  {
    return near_point(cell, cell->bounding_box(), 0.5 * cell->diameter(), p);
  }



  std::vector<Point<2>>
  find_singular_points(const std::array<const ElasticBody *, 2> &bodies,
                       const std::vector<ContactNodeState>      &contact_states)
  {
    std::set<std::pair<double, double>> local;
    // The states are those of all slave nodes on every rank.
    add_contact_zone_ends(contact_states, local);
    for (const ElasticBody *body : bodies)
      add_boundary_condition_changes(*body, local);
    // Both parts are the same on every rank.
    std::vector<Point<2>> points;
    for (const auto &[x, y] : local)
      points.emplace_back(x, y);
    return points;
  }



  OptimalSizePlanner::OptimalSizePlanner(
    const std::array<const ElasticBody *, 2> &bodies,
    const ErrorEstimate                      &estimate,
    const std::vector<Point<2>>              &singular_points,
    const unsigned int                        degree,
    const double                              singular_rate)
    : comm(bodies[0]->dof_handler().get_communicator())
    , degree(degree)
    , n_singular_cells(0)
  {
    // The cells of both bodies in one list: the optimum is over the whole
    // problem.
    const double D2 = estimate.normalisation_squared;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const auto &tria  = bodies[b]->triangulation();
        n_active_cells[b] = tria.n_active_cells();
        rate[b].reinit(tria.n_active_cells());
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const unsigned int   i     = cell->active_cell_index();
              const double         reach = 0.5 * cell->diameter();
              const BoundingBox<2> box   = cell->bounding_box();
              double               q     = degree;
              for (const auto &p : singular_points)
                if (near_point(cell, box, reach, p))
                  {
                    q = std::min<double>(degree, singular_rate);
                    ++n_singular_cells;
                    break;
                  }
              rate[b](i) = q;
              cells.push_back(
                {b,
                 i,
                 std::max(0., estimate.contribution_squared[b](i) / D2),
                 q});
            }
      }
    n_singular_cells = Utilities::MPI::sum(n_singular_cells, comm);
  }



  OptimalSizeRatios
  OptimalSizePlanner::plan(const double target_error,
                           const double min_ratio,
                           const double max_ratio,
                           const double max_n_cells,
                           const double min_n_cells) const
  {
    Assert(target_error > 0, ExcMessage("a target error is needed"));
    OptimalSizeRatios result;
    for (unsigned int b = 0; b < 2; ++b)
      result.ratio[b].reinit(n_active_cells[b]);
    result.rate             = rate;
    result.n_singular_cells = n_singular_cells;

    const SizeRatioModel model(cells, comm, degree, min_ratio, max_ratio);
    double               L = multiplier_for_error(model, target_error);
    if (max_n_cells > 0 && model.predicted_n_cells(L) > max_n_cells)
      {
        result.limited_by_max_n_cells = true;
        L = multiplier_for_cell_count(model, L, max_n_cells);
      }
    else
      {
        // Never above the cap: 'Maximum number of DoFs' wins.
        const double floor =
          max_n_cells > 0 ? std::min(min_n_cells, max_n_cells) : min_n_cells;
        if (floor > 0 && model.predicted_n_cells(L) < floor)
          {
            result.limited_by_min_n_cells = true;
            L = multiplier_for_min_cell_count(model, L, floor);
          }
      }

    double n_cells = 0;
    for (std::size_t i = 0; i < cells.size(); ++i)
      {
        const Cell  &c                = cells[i];
        const double r                = model.ratio(i, L);
        result.ratio[c.body](c.index) = r;
        n_cells += std::pow(r, -dimension);
        result.n_at_min_ratio +=
          (r <= lowest_size_ratio(min_ratio, c.rate < degree) * (1 + 1e-12));
        result.n_at_max_ratio += (r >= max_ratio * (1 - 1e-12));
      }
    result.predicted_n_cells = Utilities::MPI::sum(n_cells, comm);
    result.predicted_epsilon =
      std::sqrt(model.predicted_error_squared(L, true));
    result.n_at_min_ratio = Utilities::MPI::sum(result.n_at_min_ratio, comm);
    result.n_at_max_ratio = Utilities::MPI::sum(result.n_at_max_ratio, comm);
    return result;
  }
} // namespace coulomb_adapt
