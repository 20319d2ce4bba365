// Where a relative 'Scene/Gmsh/Mesh file' is looked for
// (app/input_file_paths.h), through read_parameters as the program reads
// its command line:
//  1. the example prm/blocks_gmsh.prm named from another directory, by an
//     absolute and by a relative path: its 'meshes/...' is the file in
//     prm/meshes (before, only a run from the repository's root found it);
//  2. a parameter file written for the directory the program runs in
//     ('prm/meshes/blocks.geo', nothing of that name beside the file):
//     the value stays, and names the file from there;
//  3. a file of that name both beside the parameter file and in the
//     directory the program runs in: the one beside the parameter file;
//  4. the same name given with -s: the one in the directory the program
//     runs in (typed in the shell);
//  5. an absolute path and a path to no file: unchanged (the scene then
//     reports the missing file).
// Every file found is named by its absolute path afterwards, so that the
// run's parameters.prm runs again from any directory (before, a -s path
// stayed relative to the directory of the first run).
// Only paths relative to the repository or to the test's own directories
// are printed, so the output is the same in every clone.

#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/app/command_line.h>
#include <coulomb_adapt/app/two_body_problem.h>

#include "test_utilities.h"

#include <filesystem>
#include <fstream>
#include <string>

using namespace coulomb_adapt;
namespace fs = std::filesystem;

namespace
{
  // The mesh file that @p parameter_file and @p settings give.
  std::string
  mesh_file(const std::string       &parameter_file,
            const testing::Settings &settings)
  {
    ParameterHandler prm;
    TwoBodyProblem::declare_parameters(prm);
    CommandLine command_line;
    command_line.parameter_file = parameter_file;
    command_line.overrides      = settings;
    read_parameters(command_line, prm);
    prm.enter_subsection("Scene");
    prm.enter_subsection("Gmsh");
    const std::string file = prm.get("Mesh file");
    prm.leave_subsection();
    prm.leave_subsection();
    return file;
  }



  void
  write_text(const fs::path &path, const std::string &text)
  {
    std::ofstream out(path);
    out << text;
  }



  std::string
  gmsh_scene_with_mesh(const std::string &mesh)
  {
    return "subsection Scene\n  set Name = gmsh\n  subsection Gmsh\n"
           "    set Mesh file = " +
           mesh + "\n  end\nend\n";
  }



  void
  check(const bool condition, const std::string &what)
  {
    AssertThrow(condition, ExcMessage(what));
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::ostream                    &out = std::cout;

  const fs::path root = fs::canonical(testing::repository_root());
  const fs::path work = fs::absolute("input_file_paths.work");
  fs::remove_all(work);
  const fs::path runs_in = work / "runs_in";
  const fs::path beside  = work / "beside";
  fs::create_directories(runs_in);
  fs::create_directories(beside);

  // 1. The example, named from the test's directory.
  fs::current_path(runs_in);
  {
    const std::string absolute = mesh_file(root / "prm/blocks_gmsh.prm", {});
    out << "1. absolute prm/blocks_gmsh.prm: the file in prm/meshes: "
        << (fs::equivalent(absolute,
                           root / "prm/meshes/blocks_structured.geo") ?
              "yes" :
              "no")
        << std::endl;
    check(fs::equivalent(absolute, root / "prm/meshes/blocks_structured.geo"),
          "absolute parameter file");

    const std::string relative_prm =
      fs::relative(root / "prm/blocks_gmsh.prm", runs_in).string();
    const std::string relative = mesh_file(relative_prm, {});
    out << "   relative prm/blocks_gmsh.prm: "
        << fs::relative(relative, root).string()
        << " in the repository, an absolute path: "
        << (fs::path(relative).is_absolute() ? "yes" : "no") << std::endl;
    check(fs::path(relative).is_absolute() &&
            fs::equivalent(relative, root / "prm/meshes/blocks_structured.geo"),
          "relative parameter file");
  }

  // 2. A file written for the directory the program runs in.
  fs::current_path(root);
  {
    write_text(beside / "root_relative.prm",
               gmsh_scene_with_mesh("prm/meshes/blocks.geo"));
    const std::string file = mesh_file(beside / "root_relative.prm", {});
    out << "2. 'prm/meshes/blocks.geo', run in the repository's root: "
        << fs::relative(file, root).string()
        << ", absolute: " << (fs::path(file).is_absolute() ? "yes" : "no")
        << std::endl;
    check(fs::path(file).is_absolute() &&
            fs::equivalent(file, root / "prm/meshes/blocks.geo"),
          "a path from the directory the program runs in");
  }

  // 3. and 4. The same name beside the file and where the program runs.
  fs::current_path(runs_in);
  {
    write_text(beside / "same_name.geo", "// beside\n");
    write_text(runs_in / "same_name.geo", "// runs in\n");
    write_text(beside / "same_name.prm", gmsh_scene_with_mesh("same_name.geo"));
    const std::string from_file = mesh_file(beside / "same_name.prm", {});
    out << "3. in both places, from the file: the one beside it: "
        << (fs::equivalent(from_file, beside / "same_name.geo") ? "yes" : "no")
        << std::endl;
    check(fs::equivalent(from_file, beside / "same_name.geo"), "beside first");

    const std::string from_option =
      mesh_file(beside / "same_name.prm",
                {{"Scene/Gmsh/Mesh file", "same_name.geo"}});
    out << "4. the same name with -s: the one where the program runs: "
        << (fs::equivalent(from_option, runs_in / "same_name.geo") ? "yes" :
                                                                     "no")
        << ", absolute: "
        << (fs::path(from_option).is_absolute() ? "yes" : "no") << std::endl;
    check(fs::path(from_option).is_absolute() &&
            fs::equivalent(from_option, runs_in / "same_name.geo"),
          "-s from where the program runs");
  }

  // 5. Absolute paths and missing files stay as written.
  {
    const std::string absolute = (root / "prm/meshes/blocks.geo").string();
    write_text(beside / "absolute.prm", gmsh_scene_with_mesh(absolute));
    const bool absolute_kept =
      mesh_file(beside / "absolute.prm", {}) == absolute;
    write_text(beside / "missing.prm", gmsh_scene_with_mesh("missing.geo"));
    const std::string missing = mesh_file(beside / "missing.prm", {});
    out << "5. an absolute path unchanged: " << (absolute_kept ? "yes" : "no")
        << "; a missing file: " << missing << std::endl;
    check(absolute_kept, "absolute path");
    check(missing == "missing.geo", "missing file");
  }

  fs::current_path(work.parent_path());
  fs::remove_all(work);
  return 0;
}
