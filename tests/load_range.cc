// Loads at the ends of the range of doubles (issue 21):
//  - inside the accepted range (stresses 1e-120 ... 1e120 MPa) the static
//    problem with zero initial gap is positively homogeneous (theory.md
//    section 6): blocks with pressures 1e-110 and 1e110 give the epsilon
//    of pressure 1 to 1e-12 (before: 1e152 gave 100 % with exit 0);
//  - outside it the run stops after the solve with a NonFiniteResult on
//    every rank, naming the body, its stress scale and over- or
//    underflow (before: 1e200 gave epsilon = nan, 1e-300 epsilon = 0 and
//    "target reached", both with exit 0);
//  - summary.json holds no NaN (written as null) in either case.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/finiteness.h>
#include <coulomb_adapt/app/two_body_problem.h>

#include "test_utilities.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>

using namespace coulomb_adapt;

namespace
{
  // Whether @p j holds a null anywhere (nlohmann writes NaN as null).
  bool
  has_null(const nlohmann::json &j)
  {
    if (j.is_null())
      return true;
    if (j.is_structured())
      for (const auto &item : j)
        if (has_null(item))
          return true;
    return false;
  }

  struct Result
  {
    double      epsilon = -1;
    std::string error;
    bool        summary_has_null = false;
  };

  Result
  run_blocks(const std::string &pressure)
  {
    ParameterHandler prm;
    const Parameters parameters =
      testing::make_parameters(prm,
                               {{"Scene/Name", "blocks"},
                                {"Scene/Blocks/Pressure", pressure},
                                {"Adaptation/Strategy", "refine"},
                                {"Adaptation/Target error", "1"},
                                {"Adaptation/Number of cycles", "2"},
                                {"Output/Write VTU", "false"},
                                {"Output/Output directory",
                                 "output-" + pressure}});
    prepare_output_directory(parameters.output.directory, MPI_COMM_WORLD);
    std::ostringstream log;
    TwoBodyProblem     problem(MPI_COMM_WORLD, parameters, prm, "test", log);
    Result             result;
    try
      {
        problem.run();
        result.epsilon = problem.last_error_estimate().epsilon;
      }
    catch (const NonFiniteResult &e)
      {
        result.error = e.what();
      }
    MPI_Barrier(MPI_COMM_WORLD);
    nlohmann::json summary;
    std::ifstream(parameters.output.directory + "/summary.json") >> summary;
    result.summary_has_null = has_null(summary);
    return result;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const Result reference = run_blocks("1");
  out << "pressure 1: epsilon = " << std::fixed << std::setprecision(6)
      << 100 * reference.epsilon << " %" << std::defaultfloat << std::endl;
  AssertThrow(reference.epsilon > 0.01 && reference.error.empty(),
              ExcMessage("the reference run failed"));
  AssertThrow(!reference.summary_has_null, ExcMessage("null in summary"));

  for (const std::string pressure : {"1e-110", "1e110"})
    {
      const Result r = run_blocks(pressure);
      const double difference =
        std::abs(r.epsilon - reference.epsilon) / reference.epsilon;
      out << "pressure " << pressure << ": epsilon = " << std::fixed
          << std::setprecision(6) << 100 * r.epsilon << " %"
          << std::defaultfloat << ", same as pressure 1 to 1e-12: "
          << (difference <= 1e-12 ? "yes" : "no")
          << ", summary.json without null: "
          << (r.summary_has_null ? "no" : "yes") << std::endl;
      AssertThrow(r.error.empty(), ExcMessage(r.error));
      AssertThrow(difference <= 1e-12, ExcMessage("not homogeneous"));
      AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
    }

  for (const auto &[pressure, kind] :
       std::vector<std::pair<std::string, std::string>>{{"1e-300", "underflow"},
                                                        {"1e-130", "underflow"},
                                                        {"1e130", "overflow"},
                                                        {"1e200", "overflow"}})
    {
      const Result r = run_blocks(pressure);
      // Every rank must have stopped the same way.
      const unsigned int n_stopped =
        Utilities::MPI::sum(r.error.empty() ? 0u : 1u, MPI_COMM_WORLD);
      const bool names_it =
        r.error.find("the stresses of body 1 (upper block) are of the "
                     "order of") != std::string::npos &&
        r.error.find(kind) != std::string::npos;
      out << "pressure " << pressure << ": stopped on " << n_stopped << "/"
          << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
          << " ranks, message names body 1 and " << kind << ": "
          << (names_it ? "yes" : "no") << ", summary.json without null: "
          << (r.summary_has_null ? "no" : "yes") << std::endl;
      AssertThrow(n_stopped == Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
                  ExcMessage("not stopped on every rank"));
      AssertThrow(names_it, ExcMessage("message: " + r.error));
      AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
    }
}
