#include <deal.II/base/function.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/blocks.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    void
    Blocks::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Blocks");
      {
        prm.declare_entry("Upper body subdivisions",
                          "4, 4",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the 100 x 100 mm upper body in x and y "
                          "(before global refinement).");
        prm.declare_entry("Lower body subdivisions",
                          "8, 8",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the 200 x 200 mm lower body in x and y "
                          "(before global refinement).");
        prm.declare_entry("Pressure",
                          "10",
                          Patterns::Double(0),
                          "Uniform pressure on the top of the upper body "
                          "(MPa), > 0: the only load, which holds it on the "
                          "lower body.");
        prm.declare_entry("Hold centre line",
                          "false",
                          Patterns::Bool(),
                          "Fix the horizontal displacement of the upper "
                          "body's nodes on x = 100 (exact by symmetry). "
                          "Needs an even number of upper cells in x.");
        declare_body_materials(prm, 130000., 0.3, 130000., 0.3);
      }
      prm.leave_subsection();
    }



    Blocks::Blocks(ParameterHandler &prm, const PlaneModel)
    {
      prm.enter_subsection("Blocks");
      {
        const std::string path = "Scene/Blocks";
        upper_subdivisions =
          get_subdivisions(prm, "Upper body subdivisions", path);
        lower_subdivisions =
          get_subdivisions(prm, "Lower body subdivisions", path);
        pressure = prm.get_double("Pressure");
        // Without it the upper body floats: the solve would end in a
        // singular system, diagnosed as a body that turns off an edge.
        require_parameter(pressure > 0,
                          path + "/Pressure",
                          pressure,
                          "> 0: the pressure is the only load, and what "
                          "holds the upper body on the lower one (with "
                          "none it floats, held by nothing)");
        hold_centre_line = prm.get_bool("Hold centre line");
        if (hold_centre_line && upper_subdivisions[0] % 2 != 0)
          throw ParameterError(path + "/Upper body subdivisions",
                               prm.get("Upper body subdivisions"),
                               "'Hold centre line' needs an even number of "
                               "cells in x, so that x = 100 is a mesh line");
        materials = parse_body_materials(prm, path);
      }
      prm.leave_subsection();
    }



    std::vector<std::string>
    Blocks::load_entries() const
    {
      return {"Scene/Blocks/Pressure"};
    }



    std::string
    Blocks::name() const
    {
      return "blocks";
    }



    void
    Blocks::create_coarse_mesh(const unsigned int body,
                               const CellType     cell_type,
                               Triangulation<2>  &tria) const
    {
      using namespace boundary_ids;
      if (body == 0)
        make_rectangle(tria,
                       Point<2>(50, 200),
                       Point<2>(150, 300),
                       upper_subdivisions,
                       {{traction_free, traction_free, contact, traction}},
                       cell_type);
      else
        make_rectangle(tria,
                       Point<2>(0, 0),
                       Point<2>(200, 200),
                       lower_subdivisions,
                       {{traction_free, traction_free, dirichlet, contact}},
                       cell_type);
    }



    BodyDescription
    Blocks::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;
      if (body == 0)
        {
          d.name         = "upper block";
          const double p = pressure;
          d.tractions.push_back({boundary_ids::traction,
                                 [p](const Point<2> &, const Tensor<1, 2> &) {
                                   return Tensor<1, 2>({0., -p});
                                 }});
          if (hold_centre_line)
            d.point_constraints.push_back(
              // The centre line above the contact face (contact nodes stay
              // free).
              {[](const Point<2> &x) {
                 return std::abs(x[0] - 100.) < 1e-8 && x[1] > 200. + 1e-8;
               },
               ComponentMask(std::vector<bool>{true, false}),
               std::array<Point<2>, 2>{
                 {Point<2>(100, 200), Point<2>(100, 300)}}});
        }
      else
        {
          d.name = "lower block";
          d.dirichlet.push_back(
            {boundary_ids::dirichlet,
             ComponentMask(2, true),
             std::make_shared<Functions::ZeroFunction<2>>(2)});
        }
      return d;
    }
  } // namespace scenes
} // namespace coulomb_adapt
