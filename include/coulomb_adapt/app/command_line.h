#ifndef coulomb_adapt_app_command_line_h
#define coulomb_adapt_app_command_line_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * What the user asked for on the command line:
   *
   *   coulomb-adapt [FILE.prm] [-s "Section/Entry=value"]...
   *   coulomb-adapt --print-parameters
   *   coulomb-adapt --help
   */
  struct CommandLine
  {
    std::string parameter_file;
    /** (path, value) pairs from `-s path=value`, in the given order. */
    std::vector<std::pair<std::string, std::string>> overrides;
    bool                                             print_parameters = false;
    bool                                             help             = false;
  };

  /** Parse argv; throws ParameterError on malformed usage. */
  CommandLine
  parse_command_line(const int argc, const char *const *argv);

  /** Usage text for `--help` and usage errors. */
  std::string
  usage();

  /**
   * Read the parameter file (if any) into @p prm, look for the input
   * files it names beside it (resolve_input_files_beside()), then apply
   * the `-s` overrides. Errors name the file or the
   * override, the entry and what is allowed.
   */
  void
  read_parameters(const CommandLine &command_line, ParameterHandler &prm);

  /**
   * Create @p directory if needed and check that every rank can write into
   * it; throws with the directory and the reason otherwise.
   */
  void
  prepare_output_directory(const std::string &directory,
                           const MPI_Comm     mpi_communicator);
} // namespace coulomb_adapt

#endif
