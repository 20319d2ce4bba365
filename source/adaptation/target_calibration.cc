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



  // A correction below 1 (the last mesh did better than its plan said)
  // is believed only beyond the safety margin: c within [safety, 1) is as
  // much the cycle-to-cycle scatter of c as a bias of the model, and
  // trusting it plans the next mesh for more than safety * epsilon_0 (hertz
  // P1, epsilon_0 = 0.5 %: c = 0.946 gave an aim of 0.502 %, the mesh
  // 0.503 %, and a third adaptation step). Corrections above 1 are taken
  // in full: they make the plan finer.
  double
  TargetCalibration::aim(const double target_error) const
  {
    const double believed = correction_factor >= 1 ?
                              correction_factor :
                              std::min(1., correction_factor / safety_factor);
    return safety_factor * target_error / believed;
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
      {
        correction_factor = std::clamp(epsilon / pending_prediction,
                                       min_correction,
                                       max_correction);
        checked           = true;
      }
    pending_prediction = -1;
  }



  double
  TargetCalibration::correction() const
  {
    return correction_factor;
  }



  bool
  TargetCalibration::model_checked() const
  {
    return checked;
  }
} // namespace coulomb_adapt
