#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/scenes/hertz.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <cmath>

namespace coulomb_adapt
{
  namespace scenes
  {
    namespace
    {
      constexpr types::manifold_id arc_manifold_id = 1;
    }



    void
    Hertz::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Hertz");
      {
        prm.declare_entry("Radius", "100", Patterns::Double(0),
                          "Radius R of the half disc (mm).");
        prm.declare_entry("Line load", "1000", Patterns::Double(0),
                          "Total load P' per unit thickness pressing the "
                          "disc down (N/mm), applied as a uniform traction "
                          "P'/(2R) on its flat top.");
        prm.declare_entry("Block width", "200", Patterns::Double(0),
                          "Width 2L of the block (mm).");
        prm.declare_entry("Block height", "100", Patterns::Double(0),
                          "Height H of the block (mm).");
        prm.declare_entry("Block subdivisions",
                          "2, 1",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Coarse cells of the block in x and y.");
        prm.declare_entry("Contact refinements",
                          "6",
                          Patterns::Integer(0, 20),
                          "Extra refinement steps of the cells near the "
                          "first contact point (quadrilateral meshes).");
        prm.declare_entry("Refined zone size",
                          "1.5",
                          Patterns::Double(0),
                          "Radius of the zone kept finest by the contact "
                          "refinements, in units of the Hertz half-width a.");
        prm.enter_subsection("Body 1");
        MaterialConstants::declare_parameters(prm, 130000., 0.3);
        prm.leave_subsection();
        prm.enter_subsection("Body 2");
        MaterialConstants::declare_parameters(prm, 130000., 0.3);
        prm.leave_subsection();
      }
      prm.leave_subsection();
    }



    Hertz::Hertz(ParameterHandler &prm, const PlaneModel plane_model)
      : plane_model(plane_model)
    {
      prm.enter_subsection("Hertz");
      {
        const std::string path = "Scene/Hertz";
        radius                 = prm.get_double("Radius");
        line_load              = prm.get_double("Line load");
        block_width            = prm.get_double("Block width");
        block_height           = prm.get_double("Block height");
        block_subdivisions =
          get_subdivisions(prm, "Block subdivisions", path);
        contact_refinements = prm.get_integer("Contact refinements");
        refined_zone_factor = prm.get_double("Refined zone size");
        for (unsigned int b = 0; b < 2; ++b)
          {
            const std::string body = "Body " + std::to_string(b + 1);
            prm.enter_subsection(body);
            materials[b].parse_parameters(prm, path + "/" + body);
            prm.leave_subsection();
          }
      }
      prm.leave_subsection();
    }



    std::string
    Hertz::name() const
    {
      return "hertz";
    }



    void
    Hertz::create_coarse_mesh(const unsigned int body,
                              const CellType     cell_type,
                              Triangulation<2> & tria) const
    {
      using namespace boundary_ids;
      if (body == 1)
        {
          make_rectangle(tria,
                         Point<2>(-block_width / 2, -block_height),
                         Point<2>(block_width / 2, 0),
                         block_subdivisions,
                         {{traction_free, traction_free, dirichlet, contact}},
                         cell_type);
          return;
        }

      // The half disc: deal.II's half ball (the half x > 0 of the disc)
      // turned by -90 degrees so that its arc points down, then lifted so
      // that it touches the block at the origin.
      Triangulation<2> quads;
      const Point<2>   centre(0, radius);
      GridGenerator::half_hyper_ball(quads, Point<2>(), radius);
      GridTools::rotate(-numbers::PI / 2, quads);
      GridTools::shift(Tensor<1, 2>({0., radius}), quads);
      quads.reset_all_manifolds();
      for (const auto &cell : quads.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const bool on_flat_top =
                std::abs(face->center()[1] - radius) < 1e-8 * radius;
              face->set_boundary_id(on_flat_top ? traction : contact);
              if (!on_flat_top)
                face->set_manifold_id(arc_manifold_id);
            }

      tria.clear();
      if (cell_type == CellType::quadrilateral)
        tria.copy_triangulation(quads);
      else
        GridGenerator::convert_hypercube_to_simplex_mesh(quads, tria);
      tria.set_manifold(arc_manifold_id, SphericalManifold<2>(centre));
    }



    void
    Hertz::refine_initial_mesh(const unsigned int,
                               Triangulation<2> &tria) const
    {
      refine_towards_point(tria,
                           Point<2>(),
                           refined_zone_factor * contact_half_width(),
                           contact_refinements);
    }



    BodyDescription
    Hertz::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;
      if (body == 0)
        {
          d.name         = "half disc";
          const double t = line_load / (2. * radius);
          d.tractions.push_back(
            {boundary_ids::traction,
             [t](const Point<2> &, const Tensor<1, 2> &) {
               return Tensor<1, 2>({0., -t});
             }});
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



    double
    Hertz::contact_half_width() const
    {
      // 1/E* = sum of (1 - nu^2)/E in plane strain, 1/E in plane stress.
      double compliance = 0;
      for (const auto &m : materials)
        compliance += (plane_model == PlaneModel::plane_strain ?
                         1. - m.poissons_ratio * m.poissons_ratio :
                         1.) /
                      m.youngs_modulus;
      const double effective_modulus = 1. / compliance;
      return std::sqrt(4. * line_load * radius /
                       (numbers::PI * effective_modulus));
    }



    double
    Hertz::peak_pressure() const
    {
      return 2. * line_load / (numbers::PI * contact_half_width());
    }
  } // namespace scenes
} // namespace coulomb_adapt
