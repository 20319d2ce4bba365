#include <coulomb_adapt/app/command_line.h>
#include <coulomb_adapt/app/input_file_paths.h>
#include <coulomb_adapt/app/parameter_suggestions.h>
#include <coulomb_adapt/core/parameter_error.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>

namespace coulomb_adapt
{



  std::string
  usage()
  {
    return "Usage: coulomb-adapt [FILE.prm] [-s \"Section/Entry=value\"]...\n"
           "       coulomb-adapt [FILE.prm] [-s ...]... --print-parameters\n"
           "\n"
           "  FILE.prm              parameter file (defaults apply without "
           "one)\n"
           "  -s \"Path/Entry=value\" override one entry; repeatable, applied "
           "after the file\n"
           "  --print-parameters    print every parameter with its "
           "documentation and value\n"
           "                        (the default, or as FILE.prm and -s set "
           "it) and stop\n";
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
            // Blanks around the names and the value, as the file parser
            // trims them ("Section/Entry = value" is the file's spelling).
            std::vector<std::string> names =
              Utilities::split_string_list(assignment.substr(0, equal), '/');
            std::string path;
            for (const auto &name : names)
              path += (path.empty() ? "" : "/") + Utilities::trim(name);
            command_line.overrides.emplace_back(
              path, Utilities::trim(assignment.substr(equal + 1)));
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



  namespace
  {
    // The declared name a misspelled one in deal.II's message about line
    // N of the file @p text probably meant: " Did you mean 'NAME'?"; or,
    // for a value that does not match its pattern, what the entry takes
    // (its documentation: deal.II names the pattern only).
    std::string
    suggestion_for_file(const std::string      &message,
                        const std::string      &text,
                        const ParameterHandler &prm)
    {
      static const std::regex entry(
        "Line <([0-9]+)>[^:]*: No entry with name <([^>]*)>");
      static const std::regex subsection(
        "Line <([0-9]+)>[^:]*: There is no such subsection to be entered: "
        "(.*)");
      static const std::regex value(
        "Line <([0-9]+)>[^:]*:[\\s\\S]*for the entry named\\s+(.*\\S)\\s+"
        "does not match");
      std::smatch match;
      if (std::regex_search(message, match, value))
        {
          const std::string path =
            subsection_path_at_line(text, std::stoul(match[1].str()));
          const std::string description =
            DeclaredParameters(prm).describe_entry(path, match[2].str());
          return description.empty() ? "" : "\n   " + description;
        }
      const bool is_entry = std::regex_search(message, match, entry);
      if (!is_entry && !std::regex_search(message, match, subsection))
        return "";
      const std::string path =
        subsection_path_at_line(text, std::stoul(match[1].str()));
      const std::string        name = match[2].str();
      const DeclaredParameters names(prm);
      if (is_entry)
        return names.suggest_entry(path, name);
      // deal.II's sentence ends with the name, without a full stop.
      const std::string suggestion = names.suggest_subsection(path, name);
      return suggestion.empty() ? "" : "." + suggestion;
    }



    // deal.II names a misspelled entry but not the entries there are.
    std::string
    unknown_entry_hint(const std::string &message)
    {
      const bool unknown =
        message.find("not yet declared") != std::string::npos ||
        message.find("No entry with name") != std::string::npos;
      return unknown ? " (--print-parameters lists the entries of every "
                       "subsection with their allowed values; "
                       "doc/parameters.md documents them)" :
                       "";
    }



    // deal.II's parser lets the last of two 'set' lines of one entry win
    // without a word (a subsection given twice merges, which is how both
    // end up in one place): a user who edits the first never sees an
    // effect. Stop on the second, with both lines.
    void
    reject_repeated_entries(const std::string &text, const std::string &file)
    {
      std::map<std::string, unsigned int> first_line;
      for (const ParameterStatement &statement : parameter_statements(text))
        if (statement.text.rfind("set ", 0) == 0 &&
            statement.text.find('=') != std::string::npos)
          {
            const std::string key =
              (statement.path.empty() ? "" : statement.path + "/") +
              Utilities::trim(
                statement.text.substr(4, statement.text.find('=') - 4));
            const auto [where, inserted] =
              first_line.emplace(key, statement.line);
            if (!inserted)
              throw ParameterError("in parameter file '" + file + "': line " +
                                   std::to_string(statement.line) + " sets '" +
                                   key + "' again (first on line " +
                                   std::to_string(where->second) +
                                   "); each entry may be set once");
          }
    }



    // Read the parameter file @p file into @p prm, with messages that
    // name the file.
    void
    read_parameter_file(const std::string &file, ParameterHandler &prm)
    {
      // What stands at the path, if not a file: a directory, a FIFO or
      // a device (/dev/null) would otherwise be reported as "not found"
      // or read as an empty file.
      std::error_code error;
      const auto      status = std::filesystem::status(file, error);
      if (!std::filesystem::exists(status))
        throw ParameterError("parameter file '" + file + "' not found");
      if (!std::filesystem::is_regular_file(status))
        throw ParameterError(
          "parameter file '" + file + "' is " +
          (std::filesystem::is_directory(status) ? "a directory" :
           std::filesystem::is_fifo(status)      ? "a FIFO (named pipe)" :
           std::filesystem::is_character_file(status) ||
               std::filesystem::is_block_file(status) ?
                                              "a device" :
                                              "not a regular file") +
          ", not a parameter file (give a .prm file)");
      std::ifstream in(file);
      if (!in)
        throw ParameterError("parameter file '" + file + "' cannot be read (" +
                             std::strerror(errno) + ")");
      std::string text((std::istreambuf_iterator<char>(in)),
                       std::istreambuf_iterator<char>());
      // Editors on some systems start UTF-8 files with a byte-order mark,
      // which deal.II's parser would report as an unknown character on
      // the first line.
      if (text.compare(0, 3, "\xEF\xBB\xBF") == 0)
        text.erase(0, 3);
      reject_repeated_entries(text, file);
      try
        {
          std::istringstream input(text);
          prm.parse_input(input, file);
        }
      catch (const std::exception &e)
        {
          const std::string message = user_message(e);
          throw ParameterError("in parameter file '" + file + "': " + message +
                               suggestion_for_file(message, text, prm) +
                               unknown_entry_hint(message));
        }
    }



    // Apply one -s "Path/Entry=value" option.
    void
    apply_override(const std::string &path,
                   const std::string &value,
                   ParameterHandler  &prm)
    {
      std::vector<std::string> sections =
        Utilities::split_string_list(path, '/');
      const std::string entry = sections.back();
      sections.pop_back();
      unsigned int depth = 0;
      // Name the first subsection on the path that does not exist
      // (deal.II would only say that the entry is not declared).
      std::vector<std::string> existing;
      for (const auto &section : sections)
        {
          std::vector<std::string> next = existing;
          next.push_back(section);
          if (!prm.subsection_path_exists(next))
            {
              std::string parent;
              for (const auto &e : existing)
                parent += (parent.empty() ? "" : "/") + e;
              throw ParameterError(
                "in option -s \"" + path + "=" + value +
                "\": there is "
                "no subsection '" +
                section + "' " +
                (parent.empty() ? std::string("at the top level") :
                                  "in '" + parent + "'") +
                "." +
                DeclaredParameters(prm).suggest_subsection(parent, section) +
                " (--print-parameters lists them)");
            }
          existing = next;
        }
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
          for (; depth > 0; --depth)
            prm.leave_subsection();
          std::string section_path;
          for (const auto &s : sections)
            section_path += (section_path.empty() ? "" : "/") + s;
          const std::string message = user_message(e);
          const bool        undeclared =
            message.find("not yet declared") != std::string::npos;
          const bool mismatch =
            message.find("does not match the given pattern") !=
            std::string::npos;
          throw ParameterError(
            "in option -s \"" + path + "=" + value + "\": " + message +
            (undeclared ?
               DeclaredParameters(prm).suggest_entry(section_path, entry) :
             mismatch ?
               DeclaredParameters(prm).describe_entry(section_path, entry) :
               std::string()) +
            unknown_entry_hint(message));
        }
      for (; depth > 0; --depth)
        prm.leave_subsection();
    }
  } // namespace



  void
  read_parameters(const CommandLine &command_line, ParameterHandler &prm)
  {
    if (!command_line.parameter_file.empty())
      {
        read_parameter_file(command_line.parameter_file, prm);
        resolve_input_files_beside(command_line.parameter_file, prm);
      }
    for (const auto &[path, value] : command_line.overrides)
      apply_override(path, value, prm);
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
