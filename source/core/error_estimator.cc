#include <coulomb_adapt/core/error_estimator.h>

namespace coulomb_adapt
{
  template <>
  const OptionNames<ErrorEstimator> &
  option_names<ErrorEstimator>()
  {
    static const OptionNames<ErrorEstimator> names = {
      {ErrorEstimator::zz, "zz"},
      {ErrorEstimator::spr, "spr"},
      {ErrorEstimator::cre, "cre"}};
    return names;
  }



  std::string
  to_string(const ErrorEstimator estimator)
  {
    return option_name(estimator);
  }



  std::vector<ErrorEstimator>
  all_error_estimators()
  {
    std::vector<ErrorEstimator> estimators;
    for (const auto &[estimator, name] : option_names<ErrorEstimator>())
      estimators.push_back(estimator);
    return estimators;
  }
} // namespace coulomb_adapt
