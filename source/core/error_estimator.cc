#include <deal.II/base/exceptions.h>

#include <coulomb_adapt/core/error_estimator.h>

namespace coulomb_adapt
{
  std::string
  to_string(const ErrorEstimator estimator)
  {
    switch (estimator)
      {
        case ErrorEstimator::zz:
          return "zz";
        case ErrorEstimator::spr:
          return "spr";
        case ErrorEstimator::cre:
          return "cre";
      }
    return "";
  }



  ErrorEstimator
  error_estimator_from_string(const std::string &name)
  {
    for (const auto e : all_error_estimators())
      if (to_string(e) == name)
        return e;
    AssertThrow(false,
                dealii::ExcMessage("Unknown error estimator '" + name +
                                   "': zz, spr or cre."));
    return ErrorEstimator::zz;
  }



  std::vector<ErrorEstimator>
  all_error_estimators()
  {
    return {ErrorEstimator::zz, ErrorEstimator::spr, ErrorEstimator::cre};
  }
} // namespace coulomb_adapt
