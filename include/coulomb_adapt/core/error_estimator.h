#ifndef coulomb_adapt_core_error_estimator_h
#define coulomb_adapt_core_error_estimator_h

#include <coulomb_adapt/core/options.h>

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

  template <>
  const OptionNames<ErrorEstimator> &
  option_names<ErrorEstimator>();

  /** "zz", "spr", "cre". */
  std::string
  to_string(const ErrorEstimator estimator);

  /** Every estimator, in the order of to_string's names. */
  std::vector<ErrorEstimator>
  all_error_estimators();
} // namespace coulomb_adapt

#endif
