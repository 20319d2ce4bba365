// A run that computes its exact error checks the bound its estimate claims
// (CycleReport::record_claimed_bound, called where the target claim is an
// upper bound: cre for mu = 0): an estimate below the cycle's exact error
// logs a warning naming both numbers and what to check, one at or above it
// logs nothing, and without an exact error nothing is checked. The
// program's own estimates never fell below (tests/cre_estimator,
// benchmarks/effectivity), so the warning is driven here with given
// numbers; tests/bad_input/expect_success.cmake fails every run whose log
// has it.

#include <deal.II/base/timer.h>

#include <coulomb_adapt/output/cycle_report.h>

#include "test_utilities.h"

#include <filesystem>
#include <sstream>

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  // CycleReport writes summary.json as cycles close: none closes here, and
  // what it wrote is removed below.
  const std::string summary =
    (std::filesystem::temp_directory_path() /
     ("claimed_bound_check_" +
      std::to_string(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)) +
      ".json"))
      .string();
  const auto run = [&](const std::optional<double> exact,
                       const double                estimate) {
    std::ostringstream log;
    ConditionalOStream pcout(log, root);
    TimerOutput        timer(MPI_COMM_WORLD,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    CycleReport report(MPI_COMM_WORLD, pcout, timer, summary, "test", "");
    report.begin_cycle(0);
    if (exact)
      {
        ExactErrorComparison c;
        c.epsilon_exact = *exact;
        c.effectivity   = estimate / *exact;
        report.record_exact_error("given", {{ErrorEstimator::cre, c}});
      }
    log.str("");
    report.record_claimed_bound(estimate);
    return log.str();
  };

  const std::string below = run(0.05, 0.049);
  const std::string equal = run(0.05, 0.05);
  const std::string above = run(0.05, 0.06);
  const std::string none  = run(std::nullopt, 0.01);
  out << "estimate 4.9 % against an exact 5 %:" << std::endl << below;
  out << "estimate 5 % against an exact 5 %: "
      << (equal.empty() ? "nothing logged" : equal) << std::endl;
  out << "estimate 6 % against an exact 5 %: "
      << (above.empty() ? "nothing logged" : above) << std::endl;
  out << "no exact error: " << (none.empty() ? "nothing logged" : none)
      << std::endl;
  if (root)
    std::filesystem::remove(summary);
  if (root)
    AssertThrow(below.find("warning: the estimate is below the exact error "
                           "it claims to bound: epsilon = 4.900 % < exact "
                           "5.000 %") != std::string::npos &&
                  equal.empty() && above.empty() && none.empty(),
                ExcMessage("the claimed bound's check is wrong"));
}
