// Helpers shared by the tests: parameters from a list of overrides, the
// repository's example inputs, and output from rank 0 only (so that
// N-rank runs print what 1 rank prints).
#ifndef coulomb_adapt_tests_test_utilities_h
#define coulomb_adapt_tests_test_utilities_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/app/command_line.h>
#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/core/parameters.h>

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  namespace testing
  {
    /** "Path/Entry" = value pairs, as `-s` options give them. */
    using Settings = std::vector<std::pair<std::string, std::string>>;

    /** The repository's top directory (COULOMB_ADAPT_TEST_DATA_DIR is its
     * tests/data). */
    inline std::string
    repository_root()
    {
      return std::string(COULOMB_ADAPT_TEST_DATA_DIR) + "/../..";
    }

    /** A file of the repository's prm/ directory: the example parameter
     * files and, in meshes/, their meshes, as a user runs them. */
    inline std::string
    example_file(const std::string &relative_path)
    {
      return repository_root() + "/prm/" + relative_path;
    }

    /** Declare all parameters and apply "Path/Entry" = value pairs the
     * way the program applies `-s` options. */
    inline Parameters
    make_parameters(
      ParameterHandler                                       &prm,
      const std::vector<std::pair<std::string, std::string>> &settings,
      const std::string &parameter_file = "")
    {
      TwoBodyProblem::declare_parameters(prm);
      CommandLine command_line;
      command_line.parameter_file = parameter_file;
      command_line.overrides      = settings;
      read_parameters(command_line, prm);
      Parameters parameters;
      parameters.parse_parameters(prm);
      return parameters;
    }

    /** A whole file as text (empty when it cannot be read). */
    inline std::string
    read_text(const std::string &path)
    {
      std::ifstream     in(path);
      std::stringstream text;
      text << in.rdbuf();
      return text.str();
    }

    inline ConditionalOStream
    root_output()
    {
      return ConditionalOStream(
        std::cout, Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
    }
  } // namespace testing
} // namespace coulomb_adapt

#endif
