// The whole program run in a test: TwoBodyProblem on "Path/Entry" = value
// overrides, with what it keeps references to (the parameters), its log
// and the summary.json it wrote. Shared by the tests that check the
// program's loop and its files rather than one component.
#ifndef coulomb_adapt_tests_program_run_h
#define coulomb_adapt_tests_program_run_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/app/two_body_problem.h>

#include "test_utilities.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  namespace testing
  {
    struct ProgramRun
    {
      ParameterHandler                prm;
      const Parameters                parameters;
      std::ostringstream              log;
      std::unique_ptr<TwoBodyProblem> problem;
      nlohmann::json                  summary;

      explicit ProgramRun(const Settings    &settings,
                          const std::string &parameter_file = "")
        : parameters(make_parameters(prm, settings, parameter_file))
      {
        prepare_output_directory(parameters.output.directory, MPI_COMM_WORLD);
        problem = std::make_unique<TwoBodyProblem>(
          MPI_COMM_WORLD, parameters, prm, "test", log);
        problem->run();
        // Rank 0 writes the summary; the others read it once it is
        // complete.
        MPI_Barrier(MPI_COMM_WORLD);
        std::ifstream(parameters.output.directory + "/summary.json") >> summary;
      }
    };
  } // namespace testing
} // namespace coulomb_adapt

#endif
