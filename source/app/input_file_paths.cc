#include <coulomb_adapt/app/input_file_paths.h>

#include <filesystem>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    /** An entry whose value names a file the program reads. */
    struct InputFileEntry
    {
      std::vector<std::string> sections;
      std::string              name;
    };

    const std::vector<InputFileEntry> input_file_entries = {
      {{"Scene", "Gmsh"}, "Mesh file"}};
  } // namespace



  void
  resolve_input_files_beside(const std::string &parameter_file,
                             ParameterHandler  &prm)
  {
    const std::filesystem::path directory =
      std::filesystem::path(parameter_file).parent_path();
    if (directory.empty())
      return; // beside the file is where the program runs
    for (const InputFileEntry &entry : input_file_entries)
      {
        for (const std::string &section : entry.sections)
          prm.enter_subsection(section);
        const std::filesystem::path value = prm.get(entry.name);
        if (!value.empty() && value.is_relative())
          {
            const std::filesystem::path beside =
              (directory / value).lexically_normal();
            std::error_code error;
            if (std::filesystem::is_regular_file(beside, error))
              prm.set(entry.name, beside.string());
          }
        for (unsigned int s = 0; s < entry.sections.size(); ++s)
          prm.leave_subsection();
      }
  }
} // namespace coulomb_adapt
