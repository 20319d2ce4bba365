// The check that guards the lift of the displacement data
// (dirichlet_data_lift.h, data_gradient_mismatch()): the lift reads the
// data's gradient, and deal.II's Function::gradient() returns zero in
// release builds where a scene does not implement it, which would make
// the lift silently wrong.
//  - the manufactured scene's sinusoidal data (the only data the FE space
//    does not interpolate exactly): gradient() agrees with the central
//    difference of the values on every Dirichlet face of its meshes (0
//    and 2 global refinements), both components, both bodies;
//  - the same values with a zero gradient (what deal.II's default gives
//    in release builds): reported on every face where the data vary;
//  - data constant along the face: a zero gradient is right and is not
//    reported; a cubic whose value and derivative vanish at the face's
//    centre, with its true gradient: not reported; a large constant plus
//    a small sinusoid with a zero gradient on a fine face: reported;
//  - the cre estimate on a scene whose data have a zero gradient (the
//    manufactured scene with its gradient() replaced) stops on every rank
//    with the message that names the body (1 and 2 ranks): the estimator
//    calls check_displacement_data_gradient() before it lifts the data;
//  - with 'CRE lift of displacement data = false' the same scene is
//    estimated (nothing reads the gradient).

#include <deal.II/base/function.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/indicator/dirichlet_data_lift.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include "contact_test_utilities.h"

#include <cmath>

using namespace coulomb_adapt;

namespace
{
  // The values of @p data with a zero gradient().
  class ZeroGradient : public Function<2>
  {
  public:
    explicit ZeroGradient(std::shared_ptr<const Function<2>> data)
      : Function<2>(2)
      , data(std::move(data))
    {}

    double
    value(const Point<2> &x, const unsigned int c) const override
    {
      return data->value(x, c);
    }

    Tensor<1, 2>
    gradient(const Point<2> &, const unsigned int) const override
    {
      return Tensor<1, 2>();
    }

  private:
    const std::shared_ptr<const Function<2>> data;
  };

  // u_0 = f(x), u_1 = 0, with f and its derivative given.
  class OfX : public Function<2>
  {
  public:
    OfX(std::function<double(double)> f, std::function<double(double)> df)
      : Function<2>(2)
      , f(std::move(f))
      , df(std::move(df))
    {}

    double
    value(const Point<2> &x, const unsigned int c) const override
    {
      return c == 0 ? f(x[0]) : 0.;
    }

    Tensor<1, 2>
    gradient(const Point<2> &x, const unsigned int c) const override
    {
      return Tensor<1, 2>({c == 0 ? df(x[0]) : 0., 0.});
    }

  private:
    const std::function<double(double)> f, df;
  };

  // The manufactured scene with its displacement data's gradient()
  // replaced by zero.
  class WithoutDataGradient : public Scene
  {
  public:
    explicit WithoutDataGradient(std::unique_ptr<Scene> scene)
      : scene(std::move(scene))
    {}

    std::string
    name() const override
    {
      return scene->name();
    }

    void
    create_coarse_mesh(const unsigned int body,
                       const CellType     cell_type,
                       Triangulation<2>  &tria) const override
    {
      scene->create_coarse_mesh(body, cell_type, tria);
    }

    void
    refine_initial_mesh(const unsigned int body,
                        Triangulation<2>  &tria) const override
    {
      scene->refine_initial_mesh(body, tria);
    }

    BodyDescription
    describe_body(const unsigned int body) const override
    {
      BodyDescription description = scene->describe_body(body);
      for (auto &condition : description.dirichlet)
        condition.displacement =
          std::make_shared<ZeroGradient>(condition.displacement);
      return description;
    }

  private:
    const std::unique_ptr<Scene> scene;
  };

  const testing::Settings manufactured = {{"Scene/Name", "manufactured"},
                                          {"Mesh/Cell type", "triangle"}};
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  for (const std::string refinements : {"0", "2"})
    {
      ParameterHandler  prm;
      testing::Settings settings = manufactured;
      settings.push_back({"Mesh/Global refinements", refinements});
      const Parameters parameters = testing::make_parameters(prm, settings);
      const auto       scene      = scenes::create_scene(parameters, prm);
      for (unsigned int b = 0; b < 2; ++b)
        {
          const BodyDescription description = scene->describe_body(b);
          AssertThrow(!description.displacement_data_interpolated_exactly &&
                        !description.dirichlet.empty(),
                      ExcMessage("manufactured: expected inexact data"));
          ElasticBody  body(MPI_COMM_SELF,
                           *scene,
                           b,
                           parameters.mesh.cell_type,
                           parameters.mesh.global_refinements,
                           parameters.finite_elements);
          unsigned int n_faces = 0, n_agree = 0, n_reported = 0;
          for (const auto &cell : body.triangulation().active_cell_iterators())
            for (const unsigned int f : cell->face_indices())
              {
                const auto face = cell->face(f);
                if (!face->at_boundary())
                  continue;
                for (const auto &condition : description.dirichlet)
                  if (condition.boundary_id == face->boundary_id())
                    {
                      const ZeroGradient zero(condition.displacement);
                      ++n_faces;
                      bool agree = true, reported = false;
                      for (unsigned int c = 0; c < 2; ++c)
                        if (condition.components[c])
                          {
                            agree =
                              agree &&
                              data_gradient_mismatch(*condition.displacement,
                                                     c,
                                                     face->vertex(0),
                                                     face->vertex(1))
                                .empty();
                            reported = reported ||
                                       !data_gradient_mismatch(zero,
                                                               c,
                                                               face->vertex(0),
                                                               face->vertex(1))
                                          .empty();
                          }
                      n_agree += agree;
                      n_reported += reported;
                    }
              }
          out << refinements << " refinements, body " << b << ": " << n_faces
              << " Dirichlet faces; gradient() agrees with the values on "
              << n_agree << "; a zero gradient reported on " << n_reported
              << std::endl;
          AssertThrow(n_faces > 0 && n_agree == n_faces &&
                        n_reported == n_faces,
                      ExcMessage("data_gradient_mismatch: wrong verdict"));
        }
    }

  // Special data on a face from (c - h/2, 0) to (c + h/2, 0).
  const auto on_face =
    [](const Function<2> &data, const double c, const double h) {
      return data_gradient_mismatch(data,
                                    0,
                                    Point<2>(c - h / 2, 0.),
                                    Point<2>(c + h / 2, 0.));
    };
  const OfX         constant_along_y([](double) { return 3.; },
                             [](double) { return 0.; });
  const std::string constant = data_gradient_mismatch(constant_along_y,
                                                      0,
                                                      Point<2>(2., 0.),
                                                      Point<2>(2., 1.));
  const OfX         cubic([](double x) { return std::pow(x - 2., 3); },
                  [](double x) { return 3 * std::pow(x - 2., 2); });
  const std::string cubic_true = on_face(cubic, 2., 0.1);
  const OfX         large_plus_small(
    [](double x) { return 0.1 + 1e-4 * std::sin(M_PI * x); },
    [](double) { return 0.; });
  const std::string fine = on_face(large_plus_small, 0.3, 1e-3);
  out << "constant along the face, zero gradient: "
      << (constant.empty() ? "not reported" : "reported: " + constant)
      << std::endl;
  out << "cubic with a stationary point at the centre, true gradient: "
      << (cubic_true.empty() ? "not reported" : "reported: " + cubic_true)
      << std::endl;
  out << "0.1 + 1e-4 sin(pi x), zero gradient, h = 1e-3: "
      << (fine.empty() ? "not reported" : "reported") << std::endl;
  AssertThrow(constant.empty() && cubic_true.empty() && !fine.empty(),
              ExcMessage("data_gradient_mismatch: wrong verdict"));

  // The cre estimate on a scene without the data's gradient stops on every
  // rank before it lifts the data; without the lift it does not read them.
  const auto cre_on_zero_gradient = [&](const bool lift) {
    ParameterHandler prm;
    const Parameters parameters = testing::make_parameters(prm, manufactured);
    const WithoutDataGradient scene(scenes::create_scene(parameters, prm));
    const ElasticBodies       bodies = make_bodies(
      MPI_COMM_WORLD, scene, parameters, parameters.mesh.global_refinements);
    for (const auto &body : bodies)
      {
        body->setup_system();
        body->assemble_system();
        body->solve(parameters.linear_solver);
      }
    const ErrorEstimate estimate = estimate_error_cre(
      body_pointers(bodies),
      nullptr,
      0.,
      parameters.error_indicator.cre_degree_increase,
      true,
      true,
      {parameters.error_indicator.cre_minimisation_tolerance,
       parameters.error_indicator.cre_exact_minimisation_up_to,
       parameters.error_indicator.cre_evaluation_degree_increase,
       lift},
      parameters.linear_solver);
    return std::make_pair(bodies[0]->name(), estimate.epsilon);
  };
  std::string message, first_body;
  try
    {
      cre_on_zero_gradient(true);
    }
  catch (const std::exception &e)
    {
      message = e.what();
    }
  const unsigned int n_stopped =
    Utilities::MPI::sum(static_cast<unsigned int>(!message.empty()),
                        MPI_COMM_WORLD);
  const auto [upper, epsilon_unlifted] = cre_on_zero_gradient(false);
  out << "cre estimate with the lift, data without their gradient: stopped "
      << "on " << n_stopped << " of "
      << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
      << " ranks; the message names the body and the way out: "
      << (message.find("body '" + upper + "'") != std::string::npos &&
              message.find("CRE lift of displacement data = false") !=
                std::string::npos ?
            "yes" :
            "no")
      << std::endl;
  out << "without the lift: estimated, epsilon > 0: "
      << (epsilon_unlifted > 0 ? "yes" : "no") << std::endl;
  AssertThrow(n_stopped == Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
              ExcMessage("the cre estimate did not stop on every rank"));
  AssertThrow(epsilon_unlifted > 0,
              ExcMessage("the cre estimate without the lift failed"));
}
