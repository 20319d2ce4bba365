#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_file.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    void
    GmshFile::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Gmsh");
      {
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "A .geo or .msh file with physical surfaces "
                          "'body 1' (upper, slave), 'body 2' and physical "
                          "curves 'dirichlet', 'traction', 'contact'.");
        prm.declare_entry("Mesh size factor",
                          "1",
                          Patterns::Double(0),
                          "Factor on the element sizes of a .geo file "
                          "(gmsh's Mesh.MeshSizeFactor); ignored for .msh.");
        prm.declare_entry("Traction",
                          "0, -10",
                          Patterns::List(Patterns::Double(), 2, 2),
                          "Uniform traction (x, y) on the 'traction' "
                          "curves (MPa).");
        declare_body_materials(prm, 130000., 0.3, 130000., 0.3);
      }
      prm.leave_subsection();
    }



    GmshFile::GmshFile(ParameterHandler &prm,
                       const PlaneModel,
                       const CellType requested_cell_type)
    {
      prm.enter_subsection("Gmsh");
      {
        const std::string path = "Scene/Gmsh";
        materials = parse_body_materials(prm, path);
        const auto t = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Traction")));
        traction     = Tensor<1, 2>({t[0], t[1]});
        const std::string file = prm.get("Mesh file");
        if (file.empty())
          throw ParameterError(path + "/Mesh file",
                               file,
                               "the gmsh scene needs a .geo or .msh file");
        // The program runs on MPI_COMM_WORLD: rank 0 reads the file.
        meshes = read_two_body_gmsh_file(file,
                                         requested_cell_type,
                                         prm.get_double("Mesh size factor"),
                                         MPI_COMM_WORLD);
      }
      prm.leave_subsection();
    }



    std::string
    GmshFile::name() const
    {
      return "gmsh";
    }



    void
    GmshFile::create_coarse_mesh(const unsigned int body,
                                 const CellType,
                                 Triangulation<2> &tria) const
    {
      meshes[body].create_triangulation(tria);
    }



    BodyDescription
    GmshFile::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.name                = "body " + std::to_string(body + 1);
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;
      const Tensor<1, 2> t  = traction;
      d.tractions.push_back(
        {boundary_ids::traction,
         [t](const Point<2> &, const Tensor<1, 2> &) { return t; }});
      d.dirichlet.push_back({boundary_ids::dirichlet,
                             ComponentMask(2, true),
                             std::make_shared<Functions::ZeroFunction<2>>(2)});
      return d;
    }
  } // namespace scenes
} // namespace coulomb_adapt
