#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/refinement_flags.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace coulomb_adapt
{
  namespace
  {
    // The decision @p decide(b, i) for each owned active cell i of body b;
    // 0 (keep) on the others.
    RefinementDecisions
    decide_per_cell(
      const std::array<const ElasticBody *, 2>                         &bodies,
      const std::function<int(const unsigned int, const unsigned int)> &decide)
    {
      RefinementDecisions decisions;
      for (unsigned int b = 0; b < 2; ++b)
        {
          const auto &tria = bodies[b]->triangulation();
          decisions[b].assign(tria.n_active_cells(), 0);
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned())
              decisions[b][cell->active_cell_index()] =
                decide(b, cell->active_cell_index());
        }
      return decisions;
    }



    // epsilon_E^2 of every cell of both bodies, on every rank, sorted
    // decreasingly: the thresholds are then the same everywhere.
    std::vector<double>
    sorted_contributions(const std::array<const ElasticBody *, 2> &bodies,
                         const ErrorEstimate                      &estimate)
    {
      const MPI_Comm      comm = bodies[0]->dof_handler().get_communicator();
      std::vector<double> local;
      for (unsigned int b = 0; b < 2; ++b)
        for (const auto &cell :
             bodies[b]->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            local.push_back(
              estimate.contribution_squared[b](cell->active_cell_index()));
      std::vector<double> all;
      for (const auto &part : Utilities::MPI::all_gather(comm, local))
        all.insert(all.end(), part.begin(), part.end());
      std::sort(all.begin(), all.end(), std::greater<double>());
      return all;
    }



    // GridRefinement's 'optimize': the number M of cells to refine that
    // minimises the predicted error times the cell count,
    // (N + 3 M)^q (total - (1 - 4^-q) sum of the M largest).
    std::size_t
    optimal_refine_count(const std::vector<double> &all,
                         const double               total,
                         const unsigned int         degree)
    {
      const std::size_t N         = all.size();
      const double      q         = degree;
      const double      reduction = 1 - std::pow(4., -q);
      double            best      = std::pow(double(N), q) * total;
      double            refined   = 0;
      std::size_t       n_refine  = 0;
      for (std::size_t M = 1; M <= N; ++M)
        {
          refined += all[M - 1];
          const double J =
            std::pow(double(N + 3 * M), q) * (total - reduction * refined);
          if (J < best)
            {
              best     = J;
              n_refine = M;
            }
        }
      return n_refine;
    }
  } // namespace

  RefinementDecisions
  decisions_from_size_ratios(const std::array<const ElasticBody *, 2> &bodies,
                             const ErrorEstimate                      &estimate,
                             const OptimalSizeRatios                  &ratios,
                             const double target_error)
  {
    const MPI_Comm comm = bodies[0]->dof_handler().get_communicator();
    // Levels for r_E: the nearest power of 2 on a log scale, at least one
    // if r_E < r_refine, at most max_levels per cycle, -1 (coarsen) if
    // r_E > 2. The lower bound of r_E (OptimalSizePlanner) is what limits
    // the levels: 3 for r_E >= 0.1 in regular cells, 5 for r_E >= 0.03 near
    // singular points, and 5 and 7 when a checked plan relaxes the bound
    // (adapt_meshes); max_levels only guards against extreme bounds. (At 5
    // it cut the relaxed plan's 7 levels near punch's corners: that mesh
    // missed its prediction by 1.6x, with 8 by 1.05x.)
    constexpr int max_levels = 8;
    auto          levels     = [&](const double r, const double r_refine) {
      if (r > 2)
        return -1;
      if (r >= r_refine)
        return 0;
      return std::clamp(static_cast<int>(std::floor(-std::log2(r) + 0.5)),
                        1,
                        max_levels);
    };
    // Predicted epsilon^2 for these levels: epsilon_E^2 x 4^(-q_E levels).
    auto predicted_error_squared = [&](const double r_refine) {
      double sum = 0;
      for (unsigned int b = 0; b < 2; ++b)
        for (const auto &cell :
             bodies[b]->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const unsigned int i = cell->active_cell_index();
              const double       r = ratios.ratio[b](i);
              const double       q = ratios.rate[b](i);
              sum += std::pow(4., -q * levels(r, r_refine)) *
                     estimate.contribution_squared[b](i);
            }
      return Utilities::MPI::sum(sum, comm) / estimate.normalisation_squared;
    };
    const double target2  = target_error * target_error;
    double       r_refine = 1 / std::sqrt(2.);
    if (predicted_error_squared(r_refine) > target2)
      {
        // The smallest threshold whose prediction meets the target.
        double low = r_refine, high = 1e3;
        for (unsigned int k = 0; k < 60; ++k)
          {
            const double mid = std::sqrt(low * high);
            (predicted_error_squared(mid) > target2 ? low : high) = mid;
          }
        // Symmetric cells have the same r_E up to round-off: a threshold
        // between them would refine one and not the other.
        r_refine = high * (1 + 1e-8);
      }

    return decide_per_cell(bodies,
                           [&](const unsigned int b, const unsigned int i) {
                             return levels(ratios.ratio[b](i), r_refine);
                           });
  }



  RefinementDecisions
  decisions_from_indicator(const std::array<const ElasticBody *, 2> &bodies,
                           const ErrorEstimate                      &estimate,
                           const RefinementCriterion                 criterion,
                           const double       refine_fraction,
                           const double       coarsen_fraction,
                           const unsigned int degree)
  {
    const std::vector<double> all = sorted_contributions(bodies, estimate);
    const std::size_t         N   = all.size();
    const double total            = std::accumulate(all.begin(), all.end(), 0.);

    // Refine the first n_refine cells, coarsen the last n_coarsen.
    std::size_t n_refine = 0, n_coarsen = 0;
    if (criterion == RefinementCriterion::fixed_fraction)
      {
        double sum = 0;
        while (n_refine < N && sum < refine_fraction * total)
          sum += all[n_refine++];
        sum = 0;
        while (n_coarsen < N - n_refine &&
               sum + all[N - 1 - n_coarsen] <= coarsen_fraction * total)
          sum += all[N - 1 - n_coarsen++];
      }
    else if (criterion == RefinementCriterion::fixed_number)
      {
        n_refine  = static_cast<std::size_t>(std::ceil(refine_fraction * N));
        n_coarsen = std::min(N - n_refine,
                             static_cast<std::size_t>(coarsen_fraction * N));
      }
    else if (criterion == RefinementCriterion::optimize)
      n_refine = optimal_refine_count(all, total, degree);
    else
      AssertThrow(false,
                  ExcMessage("refinement criterion '" + option_name(criterion) +
                             "' takes no decisions from the indicator"));

    // Cells equal up to round-off (symmetric ones) get the same decision.
    const double refine_threshold = n_refine > 0 ?
                                      all[n_refine - 1] * (1 - 1e-10) :
                                      std::numeric_limits<double>::infinity();
    const double coarsen_threshold =
      n_coarsen > 0 ? all[N - n_coarsen] * (1 + 1e-10) : -1;

    return decide_per_cell(
      bodies, [&](const unsigned int b, const unsigned int i) {
        const double e = estimate.contribution_squared[b](i);
        return e >= refine_threshold ? 1 : e <= coarsen_threshold ? -1 : 0;
      });
  }
} // namespace coulomb_adapt
