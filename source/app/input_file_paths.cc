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



    /** Set each input file entry of @p prm to @p resolve(its value) where
     * that gives a path. */
    template <typename Resolve>
    void
    for_each_input_file(ParameterHandler &prm, const Resolve &resolve)
    {
      for (const InputFileEntry &entry : input_file_entries)
        {
          for (const std::string &section : entry.sections)
            prm.enter_subsection(section);
          const std::filesystem::path value = prm.get(entry.name);
          if (!value.empty() && value.is_relative())
            {
              const std::filesystem::path resolved = resolve(value);
              if (!resolved.empty())
                prm.set(entry.name, resolved.string());
            }
          for (unsigned int s = 0; s < entry.sections.size(); ++s)
            prm.leave_subsection();
        }
    }



    /** @p path if a regular file is there, else an empty path. */
    std::filesystem::path
    if_file(const std::filesystem::path &path)
    {
      std::error_code error;
      return std::filesystem::is_regular_file(path, error) ?
               path :
               std::filesystem::path();
    }
  } // namespace



  void
  resolve_input_files_beside(const std::string &parameter_file,
                             ParameterHandler  &prm)
  {
    const std::filesystem::path directory =
      std::filesystem::path(parameter_file).parent_path();
    if (directory.empty())
      return; // beside the file is where the program runs
    for_each_input_file(prm, [&](const std::filesystem::path &value) {
      return if_file((directory / value).lexically_normal());
    });
  }



  void
  make_input_files_absolute(ParameterHandler &prm)
  {
    for_each_input_file(prm, [](const std::filesystem::path &value) {
      return if_file(value).empty() ?
               std::filesystem::path() :
               std::filesystem::absolute(value).lexically_normal();
    });
  }
} // namespace coulomb_adapt
