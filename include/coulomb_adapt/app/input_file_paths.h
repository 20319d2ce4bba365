#ifndef coulomb_adapt_app_input_file_paths_h
#define coulomb_adapt_app_input_file_paths_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The input files that @p parameter_file names with relative paths
   * (today `Scene/Gmsh/Mesh file`) are looked for beside the parameter
   * file first: such an entry of @p prm is set to the path through the
   * parameter file's directory where a file exists there. Otherwise it
   * stays as written, and is taken from the directory the program runs
   * in, as before. So `coulomb-adapt ../prm/dovetail.prm` finds
   * `meshes/dovetail.geo` from any directory, and a file written for the
   * project's root (`prm/meshes/dovetail.geo`) still runs there.
   *
   * Called after the parameter file is read and before the `-s`
   * overrides: a path given with -s is typed in the shell, so it stays
   * relative to the directory the program runs in.
   */
  void
  resolve_input_files_beside(const std::string &parameter_file,
                             ParameterHandler  &prm);

  /**
   * Every input file entry of @p prm that names an existing file by a
   * relative path (from the directory the program runs in, after
   * resolve_input_files_beside() and the -s overrides) is set to its
   * absolute path. For the run's `parameters.prm`, written after the
   * files were read (their messages name them as the user did): it then
   * names the files that were read, and runs again from any directory.
   * A path to no file stays as given.
   */
  void
  make_input_files_absolute(ParameterHandler &prm);
} // namespace coulomb_adapt

#endif
