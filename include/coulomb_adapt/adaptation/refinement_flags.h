#ifndef coulomb_adapt_adaptation_refinement_flags_h
#define coulomb_adapt_adaptation_refinement_flags_h

#include <coulomb_adapt/adaptation/optimal_size.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** What happens to each active cell of a body (entries of locally owned
   * cells): +k refine k times, -1 coarsen, 0 keep. */
  using RefinementDecisions = std::array<std::vector<signed char>, 2>;

  /**
   * Hierarchical use of the optimal size ratios (theory.md section 4):
   * a cell is refined k = round(-log2 r_E) times (at most 3 per cycle)
   * and coarsened if r_E > 2, i.e. it gets the level whose size is nearest
   * to h*_E on a logarithmic scale. Levels are coarse steps: if the error
   * predicted for these decisions (epsilon_E^2 x 4^(-q_E k)) is above
   * @p target_error, the threshold on r_E below which a cell is refined at
   * least once is raised from 2^-1/2 until it is not, so that a cycle does
   * not stall just above the target.
   */
  RefinementDecisions
  decisions_from_size_ratios(const std::array<const ElasticBody *, 2> &bodies,
                             const ErrorEstimate                      &estimate,
                             const OptimalSizeRatios                  &ratios,
                             const double target_error);

  /**
   * Decisions from epsilon_E^2 over both bodies and all ranks together
   * (deal.II's GridRefinement works on one triangulation; the two bodies
   * share one error budget):
   *
   * - "fixed fraction": the largest cells whose epsilon_E^2 sum to
   *   @p refine_fraction of epsilon^2 are refined, the smallest summing to
   *   @p coarsen_fraction coarsened;
   * - "fixed number": that fraction of the cells, by epsilon_E;
   * - "optimize": the number M of refined cells (by decreasing epsilon_E)
   *   minimising (N + 3M)^q (epsilon^2 - (1 - 4^-q) sum_{i<M}
   *   epsilon_i^2): the predicted error times the cost, with the error of a
   *   refined cell divided by 4^q (q = @p degree); no coarsening.
   */
  RefinementDecisions
  decisions_from_indicator(const std::array<const ElasticBody *, 2> &bodies,
                           const ErrorEstimate                      &estimate,
                           const RefinementCriterion                 criterion,
                           const double       refine_fraction,
                           const double       coarsen_fraction,
                           const unsigned int degree);
} // namespace coulomb_adapt

#endif
