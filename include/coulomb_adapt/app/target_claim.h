#ifndef coulomb_adapt_app_target_claim_h
#define coulomb_adapt_app_target_claim_h

#include <coulomb_adapt/core/error_estimator.h>

#include <optional>
#include <string>

namespace coulomb_adapt
{
  /**
   * What a "target reached" rests on. An adaptive run stops when the
   * estimate epsilon is below epsilon_0; whether the error itself is below
   * epsilon_0 depends on the estimator (theory.md sections 7 and 8):
   * the recovery estimates (zz, spr) are not bounds and underestimate at
   * singular points on coarse meshes (effectivity 0.6-0.8 on the seed's
   * example), cre is an upper bound for frictionless contact up to its
   * local problems' discretisation (not claimed with the relaxed
   * equilibration, which was measured 5 % below the error), and for
   * mu > 0 its effectivity is measured near 1 but not proven >= 1. Where
   * the run also computed the exact error of the cycle, that decides.
   */
  struct TargetClaim
  {
    /** "recovery estimate, not a bound", "an upper bound for mu = 0, ...", ...
     */
    std::string kind_of_estimate;
    /** Whether the estimate bounds the error from above. */
    bool is_upper_bound = false;
    /** The cycle's exact error, where computed (extrapolated if the
     * reference's levels allowed it). */
    std::optional<double> epsilon_exact;

    /** Whether the exact error, where known, is at most @p target. */
    bool
    met_by_exact_error(const double target) const;

    /** The words that follow "target reached: epsilon = ... <=
     * epsilon_0 = ... %" in the log and in summary.json's stop_reason. */
    std::string
    qualifier(const double target) const;
  };

  /** @p reaction_not_carried: cre's sigma^ misses the reaction of nodes
   * held by the scene's point constraints off any held line (point
   * supports; ErrorEstimate::misses_held_reaction()), so it is not a
   * proven bound even for mu = 0. @p degree: the elements' polynomial
   * degree (zz underestimates with degree 2). @p relaxed_equilibration
   * with @p evaluation_degree_increase = 0: cre's optimisation moved the
   * relaxed modes and the estimate was evaluated with the minimisation's
   * own local problems, where its minimum sees least of sigma^ (frictionless
   * Q1 blocks: effectivity 0.95 before the kinematic side was opened), so
   * no bound is claimed then. @p penetration_left: cre's kinematic side
   * still penetrates after the opening (ErrorEstimate::penetration_after),
   * so it is not admissible and no bound is claimed. @p negative_pressure:
   * sigma^'s pressure is negative between the nodes (quadratic segments
   * whose Bernstein form fell back to the Lagrange interpolant,
   * bernstein_contact_traction.h; ErrorEstimate::negative_pressure), so sigma^
   * is not admissible either. @p displacement_data_unlifted: a body's
   * displacement data are not interpolated exactly by the FE space and
   * 'CRE lift of displacement data' is false, so the kinematic side does
   * not meet them and no bound is claimed. */
  TargetClaim
  make_target_claim(const ErrorEstimator         estimator,
                    const double                 friction_coefficient,
                    const std::optional<double> &epsilon_exact,
                    const bool                   reaction_not_carried,
                    const unsigned int           degree,
                    const bool                   relaxed_equilibration = false,
                    const unsigned int           evaluation_degree_increase = 1,
                    const bool                   penetration_left  = false,
                    const bool                   negative_pressure = false,
                    const bool displacement_data_unlifted          = false);

  /** Why zz does not estimate the error of elements of degree @p degree
   * (>= 2), with the measured effectivities; empty for degree 1. */
  std::string
  zz_degree_warning(const unsigned int degree);
} // namespace coulomb_adapt

#endif
