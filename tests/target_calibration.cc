// TargetCalibration (adaptation/target_calibration.h) against numbers
// computed by hand: aim = safety * epsilon_0 / c', c = achieved / predicted
// of the last plan, clamped to [0.5, 2], 1 until a plan has been checked,
// and c' = c for c >= 1, min(1, c / safety) below (a correction below 1
// is believed only beyond the safety margin).
// Safety 0.8, epsilon_0 = 5 %:
//  - first cycle (no plan yet): c = 1, aim = 0.8 * 0.05 = 0.04; an
//    achieved epsilon without a plan (0.07) leaves c at 1;
//  - plan 0.04, achieved 0.05: c = 1.25, aim = 0.04 / 1.25 = 0.032; the
//    plan is used once (a second achieved 0.1 leaves c at 1.25);
//  - plan 0.032, achieved 0.016: c = 0.5 (the lower bound itself),
//    c' = 0.625, aim 0.064;
//  - plan 0.08, achieved 0.01: ratio 0.125, clamped to 0.5, aim 0.064;
//  - plan 0.04, achieved 0.034: c = 0.85, within [safety, 1): c' = 1, aim
//    0.04 (not 0.047, which is near epsilon_0);
//  - plan 0.02, achieved 0.1: ratio 5, clamped to 2, aim 0.02;
//  - plan 0.02, achieved 0.039: c = 1.95 (inside), aim = 0.04 / 1.95;
//  - plans that cannot be checked leave c: predicted 0, predicted
//    infinity, achieved 0 (which also drops its plan);
//  - two plans before one measurement: the later plan is checked
//    (plans 0.01 then 0.02, achieved 0.03: c = 1.5);
//  - safety 1, first cycle: aim = epsilon_0.
// model_checked() is false until the first plan has been checked (an
// achieved epsilon without a plan does not count), true after.
// 1 rank.

#include <coulomb_adapt/adaptation/target_calibration.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <limits>

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::setprecision(10);

  const double target = 0.05;
  // The hand values are one or two floating-point operations away from
  // the computed ones: a few ulp.
  const auto check = [&](const std::string       &step,
                         const TargetCalibration &calibration,
                         const double             expected_correction,
                         const double             expected_aim) {
    const double c   = calibration.correction();
    const double aim = calibration.aim(target);
    out << step << ": correction " << c << ", aim " << aim << std::endl;
    AssertThrow(std::abs(c - expected_correction) <=
                    4e-16 * expected_correction &&
                  std::abs(aim - expected_aim) <= 4e-16 * expected_aim,
                ExcMessage(step + ": expected correction " +
                           std::to_string(expected_correction) + ", aim " +
                           std::to_string(expected_aim)));
  };

  TargetCalibration calibration(0.8);
  check("first cycle, no plan", calibration, 1., 0.04);
  calibration.record_achieved(0.07);
  check("achieved 0.07 without a plan", calibration, 1., 0.04);
  const auto check_checked = [&](const std::string       &step,
                                 const TargetCalibration &calibration,
                                 const bool               expected) {
    out << step << ": model checked " << calibration.model_checked()
        << std::endl;
    AssertThrow(calibration.model_checked() == expected,
                ExcMessage(step + ": model_checked() is wrong"));
  };
  check_checked("before any plan", calibration, false);
  calibration.record_plan(0.04);
  check_checked("a plan, not yet measured", calibration, false);
  calibration.record_achieved(0.);
  check_checked("a plan, achieved 0", calibration, false);

  calibration.record_plan(0.04);
  calibration.record_achieved(0.05);
  check("plan 0.04, achieved 0.05", calibration, 1.25, 0.032);
  check_checked("plan 0.04, achieved 0.05", calibration, true);
  calibration.record_achieved(0.1);
  check("achieved 0.1, the plan already used", calibration, 1.25, 0.032);

  calibration.record_plan(0.032);
  calibration.record_achieved(0.016);
  check("plan 0.032, achieved 0.016 (c = 0.5, the bound)",
        calibration,
        0.5,
        0.064);

  calibration.record_plan(0.08);
  calibration.record_achieved(0.01);
  check("plan 0.08, achieved 0.01 (0.125 clamped)", calibration, 0.5, 0.064);

  calibration.record_plan(0.04);
  calibration.record_achieved(0.034);
  check("plan 0.04, achieved 0.034 (c = 0.85, within the safety margin)",
        calibration,
        0.85,
        0.04);

  calibration.record_plan(0.02);
  calibration.record_achieved(0.1);
  check("plan 0.02, achieved 0.1 (5 clamped)", calibration, 2., 0.02);

  calibration.record_plan(0.02);
  calibration.record_achieved(0.039);
  check("plan 0.02, achieved 0.039", calibration, 1.95, 0.04 / 1.95);

  calibration.record_plan(0.);
  calibration.record_achieved(0.03);
  check("plan 0, achieved 0.03 (not checked)", calibration, 1.95, 0.04 / 1.95);
  calibration.record_plan(std::numeric_limits<double>::infinity());
  calibration.record_achieved(0.03);
  check("plan inf, achieved 0.03 (not checked)",
        calibration,
        1.95,
        0.04 / 1.95);
  calibration.record_plan(0.02);
  calibration.record_achieved(0.);
  check("plan 0.02, achieved 0 (not checked)", calibration, 1.95, 0.04 / 1.95);
  calibration.record_achieved(0.03);
  check("achieved 0.03, that plan dropped", calibration, 1.95, 0.04 / 1.95);

  calibration.record_plan(0.01);
  calibration.record_plan(0.02);
  calibration.record_achieved(0.03);
  check("plans 0.01 then 0.02, achieved 0.03", calibration, 1.5, 0.04 / 1.5);

  const TargetCalibration full(1.);
  check("safety 1, first cycle", full, 1., 0.05);
}
