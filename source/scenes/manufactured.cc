#include <deal.II/base/function.h>

#include <coulomb_adapt/scenes/manufactured.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <cmath>

namespace coulomb_adapt
{
  namespace scenes
  {
    namespace
    {
      constexpr double k = numbers::PI;
    }



    ManufacturedDisplacement::ManufacturedDisplacement(const double amplitude)
      : Function<2>(2)
      , gradient_amplitude(amplitude)
      , rotational_amplitude(0.5 * amplitude)
    {}



    double
    ManufacturedDisplacement::value(const Point<2>    &p,
                                    const unsigned int component) const
    {
      const double A = gradient_amplitude, B = rotational_amplitude;
      const double sx = std::sin(k * p[0]), cx = std::cos(k * p[0]);
      const double sy = std::sin(k * p[1]), cy = std::cos(k * p[1]);
      return component == 0 ? (A + B) * sx * cy : (A - B) * cx * sy;
    }



    Tensor<1, 2>
    ManufacturedDisplacement::gradient(const Point<2>    &p,
                                       const unsigned int component) const
    {
      const double A = gradient_amplitude, B = rotational_amplitude;
      const double sx = std::sin(k * p[0]), cx = std::cos(k * p[0]);
      const double sy = std::sin(k * p[1]), cy = std::cos(k * p[1]);
      if (component == 0)
        return Tensor<1, 2>({k * (A + B) * cx * cy, -k * (A + B) * sx * sy});
      return Tensor<1, 2>({-k * (A - B) * sx * sy, k * (A - B) * cx * cy});
    }



    SymmetricTensor<2, 2>
    ManufacturedDisplacement::stress(const Point<2>        &p,
                                     const ElasticMaterial &material) const
    {
      Tensor<2, 2> grad;
      for (unsigned int c = 0; c < 2; ++c)
        grad[c] = gradient(p, c);
      return material.stress(symmetrize(grad));
    }



    Tensor<1, 2>
    ManufacturedDisplacement::body_force(const Point<2>        &p,
                                         const ElasticMaterial &material) const
    {
      const double A = gradient_amplitude, B = rotational_amplitude;
      const double sx = std::sin(k * p[0]), cx = std::cos(k * p[0]);
      const double sy = std::sin(k * p[1]), cy = std::cos(k * p[1]);
      const double a = (material.lambda() + 2. * material.mu()) * A;
      const double b = material.mu() * B;
      return 2. * k * k * Tensor<1, 2>({(a + b) * sx * cy, (a - b) * cx * sy});
    }



    void
    Manufactured::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Manufactured");
      {
        prm.declare_entry("Amplitude",
                          "0.01",
                          Patterns::Double(0),
                          "Amplitude A of the manufactured displacement "
                          "(mm).");
        prm.declare_entry("Body 1 subdivisions",
                          "2, 2",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the upper unit square in x and y.");
        prm.declare_entry("Body 2 subdivisions",
                          "3, 3",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Cells of the lower unit square in x and y.");
        declare_body_materials(prm, 1000., 0.3, 2000., 0.2);
      }
      prm.leave_subsection();
    }



    Manufactured::Manufactured(ParameterHandler &prm,
                               const PlaneModel  plane_model)
      : plane_model(plane_model)
    {
      prm.enter_subsection("Manufactured");
      {
        const std::string path = "Scene/Manufactured";
        exact                  = std::make_shared<ManufacturedDisplacement>(
          prm.get_double("Amplitude"));
        subdivisions[0] = get_subdivisions(prm, "Body 1 subdivisions", path);
        subdivisions[1] = get_subdivisions(prm, "Body 2 subdivisions", path);
        materials       = parse_body_materials(prm, path);
      }
      prm.leave_subsection();
    }



    std::vector<std::string>
    Manufactured::load_entries() const
    {
      return {"Scene/Manufactured/Amplitude"};
    }



    std::string
    Manufactured::name() const
    {
      return "manufactured";
    }



    void
    Manufactured::create_coarse_mesh(const unsigned int body,
                                     const CellType     cell_type,
                                     Triangulation<2>  &tria) const
    {
      using namespace boundary_ids;
      const double y0 = (body == 0) ? 1. : 0.;
      make_rectangle(tria,
                     Point<2>(0, y0),
                     Point<2>(1, y0 + 1),
                     subdivisions[body],
                     {{dirichlet, dirichlet, dirichlet, traction}},
                     cell_type);
    }



    BodyDescription
    Manufactured::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.name               = body == 0 ? "upper square" : "lower square";
      d.material           = materials[body];
      d.exact_displacement = exact;
      d.displacement_data_interpolated_exactly = false;
      d.dirichlet.push_back(
        {boundary_ids::dirichlet, ComponentMask(2, true), exact});

      const ElasticMaterial material(materials[body], plane_model);
      const auto            u = exact;
      d.tractions.push_back(
        {boundary_ids::traction,
         [u, material](const Point<2> &x, const Tensor<1, 2> &n) {
           return u->stress(x, material) * n;
         }});
      d.body_force = [u, material](const Point<2> &x) {
        return u->body_force(x, material);
      };
      return d;
    }
  } // namespace scenes
} // namespace coulomb_adapt
