#include <coulomb_adapt/app/target_claim.h>

#include <iomanip>
#include <sstream>

namespace coulomb_adapt
{
  TargetClaim
  make_target_claim(const ErrorEstimator         estimator,
                    const double                 friction_coefficient,
                    const std::optional<double> &epsilon_exact,
                    const bool                   reaction_not_carried)
  {
    TargetClaim claim;
    claim.epsilon_exact = epsilon_exact;
    if (estimator != ErrorEstimator::cre)
      claim.kind_of_estimate = "a recovery estimate, not a bound";
    else if (friction_coefficient == 0 && reaction_not_carried)
      // sigma^ misses point supports' reactions: admissible only up to
      // them.
      claim.kind_of_estimate =
        "an upper bound for mu = 0 up to its local problems' "
        "discretisation, but not proven here: sigma^ does not carry the "
        "reaction of the point supports";
    else if (friction_coefficient == 0)
      {
        // theory.md section 7: sigma^ statically admissible, so the CRE
        // bounds the error of frictionless contact (up to the local
        // problems' discretisation, measured below 0.5 %).
        claim.kind_of_estimate =
          "an upper bound for mu = 0, up to its local problems' "
          "discretisation";
        claim.is_upper_bound = true;
      }
    else
      claim.kind_of_estimate = "equilibrated, not a proven bound for mu > 0";
    claim.kind_of_estimate =
      to_string(estimator) + ": " + claim.kind_of_estimate;
    return claim;
  }



  bool
  TargetClaim::met_by_exact_error(const double target) const
  {
    return !epsilon_exact || *epsilon_exact <= target;
  }



  std::string
  TargetClaim::qualifier(const double target) const
  {
    std::ostringstream s;
    s << " (" << kind_of_estimate << ")";
    if (epsilon_exact)
      s << "; exact error " << std::setprecision(4) << 100 * *epsilon_exact
        << " %: "
        << (met_by_exact_error(target) ? "target met" :
                                         "target NOT met, the estimate is low");
    return s.str();
  }
} // namespace coulomb_adapt
