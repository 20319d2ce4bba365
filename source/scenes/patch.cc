#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/patch.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    void
    Patch::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Patch");
      {
        prm.declare_entry("Width",
                          "10",
                          Patterns::Double(0),
                          "Width of both blocks (mm).");
        prm.declare_entry("Upper body height",
                          "5",
                          Patterns::Double(0),
                          "Height of the upper block (mm).");
        prm.declare_entry("Lower body height",
                          "5",
                          Patterns::Double(0),
                          "Height of the lower block (mm).");
        prm.declare_entry("Upper body subdivisions",
                          "3, 2",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the upper block in x and y.");
        prm.declare_entry("Lower body subdivisions",
                          "10, 5",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the lower block in x and y; a count in "
                          "x different from the upper block's makes the "
                          "interface non-matching.");
        prm.declare_entry("Pressure",
                          "1",
                          Patterns::Double(0),
                          "Uniform pressure on top of the upper block "
                          "(MPa), > 0: what holds it on the lower block.");
        prm.declare_entry("Shear traction",
                          "0",
                          Patterns::Double(),
                          "Uniform tangential traction (+x) on top of the "
                          "upper block (MPa): a block pushed sideways. "
                          "Beyond mu times the pressure the block slides "
                          "(and the static problem has no equilibrium "
                          "unless 'Hold upper body' holds it).");
        prm.declare_entry("Hold upper body",
                          "true",
                          Patterns::Bool(),
                          "Fix the horizontal displacement of the upper "
                          "block's nodes on x = 0, where the exact solution "
                          "has none: needed without friction, where nothing "
                          "else holds the block sideways.");
        declare_body_materials(prm, 1000., 0.3, 1000., 0.3);
      }
      prm.leave_subsection();
    }



    Patch::Patch(ParameterHandler &prm, const PlaneModel)
    {
      prm.enter_subsection("Patch");
      {
        const std::string path = "Scene/Patch";
        width                  = prm.get_double("Width");
        heights[0]             = prm.get_double("Upper body height");
        heights[1]             = prm.get_double("Lower body height");
        subdivisions[0] =
          get_subdivisions(prm, "Upper body subdivisions", path);
        subdivisions[1] =
          get_subdivisions(prm, "Lower body subdivisions", path);
        pressure        = prm.get_double("Pressure");
        hold_upper_body = prm.get_bool("Hold upper body");
        // 'Hold upper body' fixes x only: the upper body rests on the
        // lower one under the pressure alone, and floats without it.
        require_parameter(pressure > 0,
                          path + "/Pressure",
                          pressure,
                          "> 0: the pressure is what holds the upper body on "
                          "the lower one ('Hold upper body' fixes x only; "
                          "with no pressure it floats, held by nothing)");
        shear_traction = prm.get_double("Shear traction");
        materials      = parse_body_materials(prm, path);
      }
      prm.leave_subsection();
    }



    std::vector<std::string>
    Patch::load_entries() const
    {
      return {"Scene/Patch/Pressure", "Scene/Patch/Shear traction"};
    }



    std::string
    Patch::name() const
    {
      return "patch";
    }



    void
    Patch::create_coarse_mesh(const unsigned int body,
                              const CellType     cell_type,
                              Triangulation<2>  &tria) const
    {
      using namespace boundary_ids;
      if (body == 0)
        make_rectangle(tria,
                       Point<2>(0, heights[1]),
                       Point<2>(width, heights[1] + heights[0]),
                       subdivisions[0],
                       {{traction_free, traction_free, contact, traction}},
                       cell_type);
      else
        make_rectangle(tria,
                       Point<2>(0, 0),
                       Point<2>(width, heights[1]),
                       subdivisions[1],
                       {{traction_free, traction_free, roller, contact}},
                       cell_type);
    }



    BodyDescription
    Patch::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;
      if (body == 0)
        {
          d.name         = "upper block";
          const double p = pressure, tau = shear_traction;
          d.tractions.push_back(
            {boundary_ids::traction,
             [p, tau](const Point<2> &, const Tensor<1, 2> &) {
               return Tensor<1, 2>({tau, -p});
             }});
          if (hold_upper_body)
            d.point_constraints.push_back(
              // The left edge above the contact face (contact nodes stay
              // free).
              {[y0 = heights[1]](const Point<2> &x) {
                 return std::abs(x[0]) < 1e-10 && x[1] > y0 * (1 + 1e-10);
               },
               ComponentMask(std::vector<bool>{true, false}),
               std::nullopt}); // a boundary edge: remeshing keeps it
        }
      else
        {
          d.name = "lower block";
          // Rollers: no vertical displacement at the base...
          d.dirichlet.push_back(
            {boundary_ids::roller,
             ComponentMask(std::vector<bool>{false, true}),
             std::make_shared<Functions::ZeroFunction<2>>(2)});
          // ...and the lower left corner held horizontally.
          d.point_constraints.push_back(
            {[](const Point<2> &x) { return x.norm() < 1e-10; },
             ComponentMask(std::vector<bool>{true, false}),
             std::nullopt}); // a boundary corner: remeshing keeps it
        }
      return d;
    }
  } // namespace scenes
} // namespace coulomb_adapt
