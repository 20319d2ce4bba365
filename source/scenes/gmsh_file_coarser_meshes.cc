#include <coulomb_adapt/scenes/gmsh_file.h>

#include <cmath>
#include <filesystem>

// The coarser meshes of a .geo scene for the nested iteration
// (Contact/Nested iteration levels): the same file meshed by gmsh at
// 'Mesh size factor' x 2^k. Apart from gmsh_file.cc, which reads the
// scene's own mesh, because it serves the solver, not the scene's
// description.
namespace coulomb_adapt
{
  namespace scenes
  {
    std::unique_ptr<Scene>
    GmshFile::with_coarser_graded_meshes(const unsigned int k) const
    {
      const std::string extension =
        std::filesystem::path(mesh_file).extension().string();
      if (extension == ".msh" || extension == ".MSH")
        return nullptr;
      auto &coarser_geometry = coarser_geometries[k];
      if (!coarser_geometry)
        {
          // A size the file's geometry cannot be meshed with (dovetail's
          // quadrangles at 8x: "gmsh cannot read it") is no coarser mesh.
          // The reader's errors reach every rank alike.
          try
            {
              coarser_geometry = std::make_shared<const TwoBodyGmshMeshes>(
                read_two_body_gmsh_geometry(mesh_file,
                                            requested_cell_type,
                                            size_factor * std::pow(2., k),
                                            group_use,
                                            MPI_COMM_WORLD));
            }
          catch (const std::exception &)
            {
              return nullptr;
            }
        }
      auto coarser         = std::make_unique<GmshFile>(*this);
      coarser->size_factor = size_factor * std::pow(2., k);
      coarser->geometry    = *coarser_geometry;
      coarser->coarser_geometries.clear();
      return coarser;
    }
  } // namespace scenes
} // namespace coulomb_adapt
