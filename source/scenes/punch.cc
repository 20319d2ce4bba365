#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/punch.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    void
    Punch::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Punch");
      {
        prm.declare_entry("Punch width",
                          "20",
                          Patterns::Double(0),
                          "Width w of the punch (mm).");
        prm.declare_entry("Punch height",
                          "10",
                          Patterns::Double(0),
                          "Height h of the punch (mm).");
        prm.declare_entry("Block width",
                          "100",
                          Patterns::Double(0),
                          "Width 2L of the block (mm).");
        prm.declare_entry("Block height",
                          "50",
                          Patterns::Double(0),
                          "Height H of the block (mm).");
        prm.declare_entry("Punch subdivisions",
                          "4, 2",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the punch in x and y.");
        prm.declare_entry("Block subdivisions",
                          "10, 5",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the block in x and y.");
        prm.declare_entry("Pressure",
                          "100",
                          Patterns::Double(0),
                          "Uniform pressure on top of the punch (MPa), > 0: "
                          "the only load, which holds it on the block.");
        prm.declare_entry("Hold centre line",
                          "true",
                          Patterns::Bool(),
                          "Fix the horizontal displacement of the punch's "
                          "nodes on x = 0 (exact by symmetry); needs an "
                          "even number of punch cells in x.");
        declare_body_materials(prm, 1300000., 0.3, 130000., 0.3);
      }
      prm.leave_subsection();
    }



    Punch::Punch(ParameterHandler &prm, const PlaneModel)
    {
      prm.enter_subsection("Punch");
      {
        const std::string path = "Scene/Punch";
        punch_width            = prm.get_double("Punch width");
        punch_height           = prm.get_double("Punch height");
        block_width            = prm.get_double("Block width");
        block_height           = prm.get_double("Block height");
        subdivisions[0] = get_subdivisions(prm, "Punch subdivisions", path);
        subdivisions[1] = get_subdivisions(prm, "Block subdivisions", path);
        pressure        = prm.get_double("Pressure");
        for (const auto &[entry, value] :
             {std::pair<std::string, double>{"Punch width", punch_width},
              {"Punch height", punch_height},
              {"Block width", block_width},
              {"Block height", block_height}})
          require_parameter(value > 0,
                            path + "/" + entry,
                            value,
                            "> 0 (mm): a body of zero extent has no cells");
        // The punch is the slave body: mortar contact checks its nodes
        // against the block's face, and a slave node beyond the block's
        // edge faces nothing and stays open. Wider than the block, the
        // punch would let the block's corners pass into it unseen (a
        // walkthrough: 0.58 mm of overlap, exit 0, no warning).
        require_parameter(punch_width <= block_width,
                          path + "/Punch width",
                          punch_width,
                          "at most 'Block width' (" +
                            format_value(block_width) +
                            " mm): the punch's nodes are the contact's "
                            "slave nodes, and where its face overhangs the "
                            "block the block's corners would pass into it "
                            "unseen");
        // Without it the punch floats: the solve would end in a singular
        // system, diagnosed as a body that turns off an edge.
        require_parameter(pressure > 0,
                          path + "/Pressure",
                          pressure,
                          "> 0: the pressure is the only load, and what "
                          "holds the punch on the block (with none it "
                          "floats, held by nothing)");
        hold_centre_line = prm.get_bool("Hold centre line");
        if (hold_centre_line && subdivisions[0][0] % 2 != 0)
          throw ParameterError(path + "/Punch subdivisions",
                               prm.get("Punch subdivisions"),
                               "'Hold centre line' needs an even number of "
                               "cells in x, so that x = 0 is a mesh line");
        materials = parse_body_materials(prm, path);
      }
      prm.leave_subsection();
    }



    std::vector<std::string>
    Punch::load_entries() const
    {
      return {"Scene/Punch/Pressure"};
    }



    std::string
    Punch::name() const
    {
      return "punch";
    }



    void
    Punch::create_coarse_mesh(const unsigned int body,
                              const CellType     cell_type,
                              Triangulation<2>  &tria) const
    {
      using namespace boundary_ids;
      if (body == 0)
        make_rectangle(tria,
                       Point<2>(-punch_width / 2, 0),
                       Point<2>(punch_width / 2, punch_height),
                       subdivisions[0],
                       {{traction_free, traction_free, contact, traction}},
                       cell_type);
      else
        make_rectangle(tria,
                       Point<2>(-block_width / 2, -block_height),
                       Point<2>(block_width / 2, 0),
                       subdivisions[1],
                       {{traction_free, traction_free, dirichlet, contact}},
                       cell_type);
    }



    BodyDescription
    Punch::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;
      if (body == 0)
        {
          d.name         = "punch";
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
                 return std::abs(x[0]) < 1e-10 && x[1] > 1e-10;
               },
               ComponentMask(std::vector<bool>{true, false}),
               std::array<Point<2>, 2>{
                 {Point<2>(0, 0), Point<2>(0, punch_height)}}});
        }
      else
        {
          d.name = "block";
          d.dirichlet.push_back(
            {boundary_ids::dirichlet,
             ComponentMask(2, true),
             std::make_shared<Functions::ZeroFunction<2>>(2)});
        }
      return d;
    }
  } // namespace scenes
} // namespace coulomb_adapt
