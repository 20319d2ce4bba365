#include <coulomb_adapt/app/command_line.h>
#include <coulomb_adapt/core/parameter_error.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace coulomb_adapt
{



  std::string
  usage()
  {
    return "Usage: coulomb-adapt [FILE.prm] [-s \"Section/Entry=value\"]...\n"
           "       coulomb-adapt --print-parameters\n"
           "\n"
           "  FILE.prm              parameter file (defaults apply without "
           "one)\n"
           "  -s \"Path/Entry=value\" override one entry; repeatable, applied "
           "after the file\n"
           "  --print-parameters    print every parameter with its default "
           "and documentation\n";
  }



  CommandLine
  parse_command_line(const int argc, const char *const *argv)
  {
    CommandLine command_line;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--print-parameters")
          command_line.print_parameters = true;
        else if (arg == "-h" || arg == "--help")
          command_line.help = true;
        else if (arg == "-s" || arg == "--set")
          {
            if (i + 1 >= argc)
              throw ParameterError("option -s needs an argument "
                                   "\"Section/Entry=value\"\n" +
                                   usage());
            const std::string assignment = argv[++i];
            const auto        equal      = assignment.find('=');
            if (equal == std::string::npos || equal == 0)
              throw ParameterError("option -s '" + assignment +
                                   "': expected \"Section/Entry=value\"");
            command_line.overrides.emplace_back(assignment.substr(0, equal),
                                                assignment.substr(equal + 1));
          }
        else if (!arg.empty() && arg[0] == '-')
          throw ParameterError("unknown option '" + arg + "'\n" + usage());
        else if (command_line.parameter_file.empty())
          command_line.parameter_file = arg;
        else
          throw ParameterError("more than one parameter file given ('" +
                               command_line.parameter_file + "', '" + arg +
                               "')\n" + usage());
      }
    return command_line;
  }



  void
  read_parameters(const CommandLine &command_line, ParameterHandler &prm)
  {
    const std::string &file = command_line.parameter_file;
    if (!file.empty())
      {
        if (!std::filesystem::is_regular_file(file))
          throw ParameterError("parameter file '" + file + "' not found");
        try
          {
            prm.parse_input(file);
          }
        catch (const std::exception &e)
          {
            throw ParameterError("in parameter file '" + file +
                                 "': " + user_message(e));
          }
      }

    for (const auto &[path, value] : command_line.overrides)
      {
        std::vector<std::string> sections =
          Utilities::split_string_list(path, '/');
        const std::string entry = sections.back();
        sections.pop_back();
        unsigned int depth = 0;
        try
          {
            for (const auto &s : sections)
              {
                prm.enter_subsection(s);
                ++depth;
              }
            prm.set(entry, value);
          }
        catch (const std::exception &e)
          {
            throw ParameterError("in option -s \"" + path + "=" + value +
                                 "\": " + user_message(e));
          }
        for (; depth > 0; --depth)
          prm.leave_subsection();
      }
  }



  void
  prepare_output_directory(const std::string &directory,
                           const MPI_Comm     mpi_communicator)
  {
    std::string problem;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::error_code error;
        std::filesystem::create_directories(directory, error);
        if (error)
          problem = "cannot create it: " + error.message();
        else
          {
            const std::string probe = directory + "/.coulomb-adapt-probe";
            std::ofstream     out(probe);
            if (!(out << "probe"))
              problem = "cannot write into it";
            out.close();
            std::filesystem::remove(probe, error);
          }
      }
    problem = Utilities::MPI::broadcast(mpi_communicator, problem, 0);
    if (!problem.empty())
      throw ParameterError("Output/Output directory",
                           directory,
                           problem +
                             " (give a writable directory, e.g. with -s "
                             "\"Output/Output directory=/tmp/run\")");
  }
} // namespace coulomb_adapt
