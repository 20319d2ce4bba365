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
// The run's parameters.prm (make_input_files_absolute, as main() calls it
// before writing it) names every file found by its absolute path, so that
// it runs again from any directory (before, a -s path stayed relative to
// the directory of the first run); the values read, which the messages
// show, stay as above.
// Only paths relative to the repository or to the test's own directories
// are printed, so the output is the same in every clone.

#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/app/input_file_paths.h>

#include "test_utilities.h"

#include <filesystem>
#include <fstream>
#include <string>

using namespace coulomb_adapt;
namespace fs = std::filesystem;

namespace
{
  struct MeshFile
  {
    // As read (the program reads this file, its messages name it so).
    std::string read;
    // As parameters.prm records it.
    std::string recorded;
  };

  std::string
  get_mesh_file(ParameterHandler &prm)
  {
    prm.enter_subsection("Scene");
    prm.enter_subsection("Gmsh");
    const std::string file = prm.get("Mesh file");
    prm.leave_subsection();
    prm.leave_subsection();
    return file;
  }

  // The mesh file that @p parameter_file and @p settings give.
  MeshFile
  mesh_file(const std::string       &parameter_file,
            const testing::Settings &settings)
  {
    ParameterHandler prm;
    testing::make_parameters(prm, settings, parameter_file);
    MeshFile file;
    file.read = get_mesh_file(prm);
    make_input_files_absolute(prm);
    file.recorded = get_mesh_file(prm);
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



  // "absolute, the file FILE" for a recorded path @p recorded of
  // @p expected.
  std::string
  recorded(const std::string &recorded, const fs::path &expected)
  {
    const bool right =
      fs::path(recorded).is_absolute() && fs::equivalent(recorded, expected);
    check(right, "parameters.prm would not name " + expected.string());
    return right ? "absolute, the same file" : "wrong";
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
  const fs::path structured = root / "prm/meshes/blocks_structured.geo";

  // 1. The example, named from the test's directory.
  fs::current_path(runs_in);
  {
    const MeshFile absolute = mesh_file(root / "prm/blocks_gmsh.prm", {});
    const bool     found    = fs::equivalent(absolute.read, structured);
    out << "1. absolute prm/blocks_gmsh.prm: the file in prm/meshes: "
        << (found ? "yes" : "no")
        << "; recorded: " << recorded(absolute.recorded, structured)
        << std::endl;
    check(found, "absolute parameter file");

    const std::string relative_prm =
      fs::relative(root / "prm/blocks_gmsh.prm", runs_in).string();
    const MeshFile relative = mesh_file(relative_prm, {});
    out << "   relative prm/blocks_gmsh.prm: read as "
        << fs::relative(relative.read, fs::relative(root, runs_in)).string()
        << " through the repository, a relative path: "
        << (fs::path(relative.read).is_relative() ? "yes" : "no")
        << "; recorded: " << recorded(relative.recorded, structured)
        << std::endl;
    check(fs::path(relative.read).is_relative() &&
            fs::equivalent(relative.read, structured),
          "relative parameter file");
  }

  // 2. A file written for the directory the program runs in.
  fs::current_path(root);
  {
    write_text(beside / "root_relative.prm",
               gmsh_scene_with_mesh("prm/meshes/blocks.geo"));
    const MeshFile file = mesh_file(beside / "root_relative.prm", {});
    out << "2. 'prm/meshes/blocks.geo', run in the repository's root: read as "
        << file.read << "; recorded: "
        << recorded(file.recorded, root / "prm/meshes/blocks.geo") << std::endl;
    check(file.read == "prm/meshes/blocks.geo",
          "a path from the directory the program runs in");
  }

  // 3. and 4. The same name beside the file and where the program runs.
  fs::current_path(runs_in);
  {
    write_text(beside / "same_name.geo", "// beside\n");
    write_text(runs_in / "same_name.geo", "// runs in\n");
    write_text(beside / "same_name.prm", gmsh_scene_with_mesh("same_name.geo"));
    const MeshFile from_file = mesh_file(beside / "same_name.prm", {});
    const bool     beside_first =
      fs::equivalent(from_file.read, beside / "same_name.geo");
    out << "3. in both places, from the file: the one beside it: "
        << (beside_first ? "yes" : "no") << "; recorded: "
        << recorded(from_file.recorded, beside / "same_name.geo") << std::endl;
    check(beside_first, "beside first");

    const MeshFile from_option =
      mesh_file(beside / "same_name.prm",
                {{"Scene/Gmsh/Mesh file", "same_name.geo"}});
    out << "4. the same name with -s: read as " << from_option.read
        << "; recorded: "
        << recorded(from_option.recorded, runs_in / "same_name.geo")
        << " (the one where the program runs)" << std::endl;
    check(from_option.read == "same_name.geo", "-s stays as typed");
  }

  // 5. Absolute paths and missing files stay as written.
  {
    const std::string absolute = (root / "prm/meshes/blocks.geo").string();
    write_text(beside / "absolute.prm", gmsh_scene_with_mesh(absolute));
    const MeshFile kept = mesh_file(beside / "absolute.prm", {});
    const bool     absolute_kept =
      kept.read == absolute && kept.recorded == absolute;
    write_text(beside / "missing.prm", gmsh_scene_with_mesh("missing.geo"));
    const MeshFile missing = mesh_file(beside / "missing.prm", {});
    out << "5. an absolute path unchanged: " << (absolute_kept ? "yes" : "no")
        << "; a missing file: " << missing.read << ", recorded "
        << missing.recorded << std::endl;
    check(absolute_kept, "absolute path");
    check(missing.read == "missing.geo" && missing.recorded == "missing.geo",
          "missing file");
  }

  fs::current_path(work.parent_path());
  fs::remove_all(work);
  return 0;
}
