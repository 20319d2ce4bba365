#include <deal.II/base/exceptions.h>

#include <coulomb_adapt/adaptation/target_calibration.h>

#include <algorithm>
#include <cmath>

namespace coulomb_adapt
{
  TargetCalibration::TargetCalibration(const double safety_factor)
    : safety_factor(safety_factor)
  {
    Assert(safety_factor > 0 && safety_factor <= 1,
           dealii::ExcMessage("the safety factor must lie in (0, 1]"));
  }



  double
  TargetCalibration::aim(const double target_error) const
  {
    return safety_factor * target_error / correction_factor;
  }



  void
  TargetCalibration::record_plan(const double predicted_epsilon)
  {
    pending_prediction = predicted_epsilon;
  }



  void
  TargetCalibration::record_achieved(const double epsilon)
  {
    // Only a plan that predicted a positive, finite error can be checked;
    // the finiteness of epsilon is checked where it is computed.
    if (pending_prediction > 0 && std::isfinite(pending_prediction) &&
        epsilon > 0)
      correction_factor = std::clamp(epsilon / pending_prediction,
                                     min_correction,
                                     max_correction);
    pending_prediction = -1;
  }



  double
  TargetCalibration::correction() const
  {
    return correction_factor;
  }
} // namespace coulomb_adapt
