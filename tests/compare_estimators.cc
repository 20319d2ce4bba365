// `Error indicator/Compare estimators = true` computes zz, spr and cre on
// the same solution, the compared ones reusing the driving estimator's
// corrected contact fields (issue 17 item 2). Checked on blocks (mu = 0.3,
// P1, 2 x 2 / 4 x 4 rectangles):
//  - every estimator's epsilon, volume parts and contact part in
//    summary.json's `estimators` equal those of a run with that estimator
//    alone to 1e-12 (relative): sharing the correction changes nothing;
//  - the driving estimator is the one named by `Estimator`, whichever it is;
//  - with `Compute exact error`, each estimator's effectivity is its
//    epsilon over the exact error of the corrected solution it judges
//    (the same seed's corrected solution for all three).
// The 2-rank run prints what the 1-rank run prints (the exact error to 4
// digits: its reference solve's iterative solver differs between rank
// counts at 1e-5).

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/two_body_problem.h>

#include "program_run.h"
#include "test_utilities.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

using namespace coulomb_adapt;

namespace
{
  // The first cycle's record of a run of blocks with @p extra settings.
  nlohmann::json
  run_cycle(const std::vector<std::pair<std::string, std::string>> &extra,
            const std::string                                      &directory)
  {
    std::vector<std::pair<std::string, std::string>> settings = {
      {"Scene/Name", "blocks"},
      {"Scene/Blocks/Upper body subdivisions", "2, 2"},
      {"Scene/Blocks/Lower body subdivisions", "4, 4"},
      {"Contact/Friction coefficient", "0.3"},
      {"Mesh/Cell type", "triangle"},
      {"Adaptation/Number of cycles", "1"},
      {"Output/Write VTU", "false"},
      {"Output/Output directory", directory}};
    settings.insert(settings.end(), extra.begin(), extra.end());
    const testing::ProgramRun run(settings);
    return run.summary["cycles"][0];
  }

  void
  check_equal(const double       compared,
              const double       alone,
              const std::string &what)
  {
    AssertThrow(std::abs(compared - alone) <= 1e-12 * std::abs(alone),
                ExcMessage(what + ": the compared value differs from the "
                                  "estimator run alone"));
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::setprecision(10);

  const std::vector<std::string>        names = {"zz", "spr", "cre"};
  std::map<std::string, nlohmann::json> alone;
  for (const auto &name : names)
    alone[name] =
      run_cycle({{"Error indicator/Estimator", name}}, "output-" + name);

  for (const std::string driving : {"zz", "cre"})
    {
      const nlohmann::json cycle =
        run_cycle({{"Error indicator/Estimator", driving},
                   {"Error indicator/Compare estimators", "true"},
                   {"Error indicator/Compute exact error", "true"},
                   {"Error indicator/Reference refinements", "2"}},
                  "output-compare-" + driving);
      out << "Estimator = " << driving << ", Compare estimators = true"
          << std::endl;
      AssertThrow(cycle["estimator"].get<std::string>() == driving,
                  ExcMessage("the driving estimator is not the named one"));
      check_equal(cycle["epsilon"].get<double>(),
                  alone[driving]["epsilon"].get<double>(),
                  "driving epsilon");
      for (const auto &name : names)
        {
          const nlohmann::json &c = cycle["estimators"][name];
          const nlohmann::json &a = alone[name];
          check_equal(c["epsilon"].get<double>(),
                      a["epsilon"].get<double>(),
                      name + " epsilon");
          check_equal(c["epsilon_contact"].get<double>(),
                      a["epsilon_contact"].get<double>(),
                      name + " epsilon_contact");
          for (unsigned int b = 0; b < 2; ++b)
            check_equal(c["epsilon_volume"][b].get<double>(),
                        a["epsilon_volume"][b].get<double>(),
                        name + " epsilon_volume");
          const double theta = c["effectivity"].get<double>();
          const double exact = c["epsilon_exact"].get<double>();
          check_equal(exact,
                      cycle["epsilon_exact"].get<double>(),
                      name + " epsilon_exact (one corrected solution)");
          AssertThrow(std::abs(theta - c["epsilon"].get<double>() / exact) <=
                        1e-12 * theta,
                      ExcMessage("effectivity is not epsilon / exact"));
          out << "  " << name
              << ": epsilon = " << 100 * c["epsilon"].get<double>()
              << " % (alone " << 100 * a["epsilon"].get<double>()
              << " %), contact " << 100 * c["epsilon_contact"].get<double>()
              << std::setprecision(4) << " %, exact " << 100 * exact
              << " %, effectivity " << theta << std::setprecision(10)
              << std::endl;
        }
    }
}
