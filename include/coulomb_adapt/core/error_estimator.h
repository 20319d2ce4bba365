#ifndef coulomb_adapt_core_error_estimator_h
#define coulomb_adapt_core_error_estimator_h

#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** The a posteriori estimators of the program (`Error indicator/Estimator`).
   */
  enum class ErrorEstimator
  {
    /** The seed's: global L2 projection of the corrected stress. */
    zz,
    /** Superconvergent patch recovery instead of the projection. */
    spr,
    /** Error in constitutive relation with an equilibrated stress. */
    cre
  };

  /** "zz", "spr", "cre". */
  std::string
  to_string(const ErrorEstimator estimator);

  /** The inverse of to_string; throws for any other name. */
  ErrorEstimator
  error_estimator_from_string(const std::string &name);

  /** Every estimator, in the order of to_string's names. */
  std::vector<ErrorEstimator>
  all_error_estimators();
} // namespace coulomb_adapt

#endif
