#include <deal.II/base/mpi.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/gmsh_two_body_reader.h>

#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>
#include <gmsh.h>

#include <filesystem>

namespace coulomb_adapt
{
  std::string
  gmsh_error_message(const std::string &thrown)
  {
    // gmsh's API throws its error message as a std::string (or, for some
    // errors, an int); its logger holds the last error in either case.
    std::string last_error;
    try
      {
        gmsh::logger::getLastError(last_error);
      }
    catch (...)
      {}
    std::string message = last_error.empty() ? thrown : last_error;
    while (!message.empty() &&
           (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    return message.empty() ? "an error without a message" : message;
  }



  TwoBodyGmshMeshes
  read_two_body_gmsh_geometry(const std::string  &file_name,
                              const CellType      requested_cell_type,
                              const double        mesh_size_factor,
                              const GmshGroupUse &use,
                              const MPI_Comm      comm)
  {
    if (!std::filesystem::is_regular_file(file_name))
      throw ParameterError("Scene/Gmsh/Mesh file",
                           file_name,
                           "no such file (give a .geo or .msh file; a "
                           "relative path in a parameter file is looked for "
                           "beside that file, then in the directory the "
                           "program runs in; one given with -s in the "
                           "directory the program runs in)");

    // One rank reads (gmsh is serial, and meshing a .geo on every rank
    // would only repeat the work); every rank then either gets the meshes
    // or throws the same error, so none waits for another that gave up.
    TwoBodyGmshMeshes result;
    std::string       error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 0);
        try
          {
            result = read_two_body_model(file_name,
                                         requested_cell_type,
                                         mesh_size_factor,
                                         use);
          }
        catch (const ParameterError &e)
          {
            error = e.what();
          }
        catch (const std::exception &e)
          {
            error = "gmsh file '" + file_name + "': " + user_message(e);
          }
        catch (const std::string &e)
          {
            error = "gmsh file '" + file_name +
                    "': gmsh cannot read it: " + gmsh_error_message(e);
          }
        catch (...)
          {
            error = "gmsh file '" + file_name +
                    "': gmsh cannot read it: " + gmsh_error_message("");
          }
        gmsh::finalize();
      }
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        error = Utilities::MPI::broadcast(comm, error, 0);
        if (error.empty())
          result = Utilities::MPI::broadcast(comm, result, 0);
      }
    if (!error.empty())
      throw ParameterError(error);
    return result;
  }



  std::array<CoarseMeshData, 2>
  read_two_body_gmsh_file(const std::string &file_name,
                          const CellType     requested_cell_type,
                          const double       mesh_size_factor,
                          const MPI_Comm     comm)
  {
    return read_two_body_gmsh_geometry(file_name,
                                       requested_cell_type,
                                       mesh_size_factor,
                                       GmshGroupUse(),
                                       comm)
      .meshes;
  }
} // namespace coulomb_adapt
