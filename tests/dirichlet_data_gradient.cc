// The check that guards the lift of the displacement data
// (dirichlet_data_lift.h, data_gradient_mismatch()): the lift reads the
// data's gradient, and deal.II's Function::gradient() returns zero in
// release builds where a scene does not implement it, which would make
// the lift silently wrong.
//  - the manufactured scene's sinusoidal data (the only data the FE space
//    does not interpolate exactly): gradient() agrees with the central
//    difference of the values on every Dirichlet face of its meshes, both
//    components, both bodies;
//  - the same values without a gradient() (deal.II's default): reported
//    on a face where the data vary along it, with the two derivatives;
//  - data constant along the face: a zero gradient is right there and is
//    not reported.

#include <deal.II/base/function.h>

#include <coulomb_adapt/indicator/dirichlet_data_lift.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  // The values of @p data, and deal.II's default gradient().
  class ValuesOnly : public Function<2>
  {
  public:
    explicit ValuesOnly(const Function<2> &data)
      : Function<2>(2)
      , data(data)
    {}

    double
    value(const Point<2> &x, const unsigned int c) const override
    {
      return data.value(x, c);
    }

  private:
    const Function<2> &data;
  };

  // u = (x^2, 0): constant along the line x = const.
  class ConstantAlongVerticalLines : public Function<2>
  {
  public:
    ConstantAlongVerticalLines()
      : Function<2>(2)
    {}

    double
    value(const Point<2> &x, const unsigned int c) const override
    {
      return c == 0 ? x[0] * x[0] : 0.;
    }
  };
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  ParameterHandler prm;
  const Parameters parameters =
    testing::make_parameters(prm,
                             {{"Scene/Name", "manufactured"},
                              {"Mesh/Cell type", "triangle"},
                              {"Mesh/Global refinements", "1"}});
  const auto scene = scenes::create_scene(parameters, prm);
  for (unsigned int b = 0; b < 2; ++b)
    {
      const BodyDescription description = scene->describe_body(b);
      AssertThrow(!description.displacement_data_interpolated_exactly &&
                    !description.dirichlet.empty(),
                  ExcMessage("manufactured: expected inexact data"));
      ElasticBody  body(MPI_COMM_WORLD,
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
                  const Tensor<1, 2> edge = face->vertex(1) - face->vertex(0);
                  const double       h    = edge.norm();
                  const ValuesOnly   without_gradient(*condition.displacement);
                  ++n_faces;
                  bool agree = true, reported = false;
                  for (unsigned int c = 0; c < 2; ++c)
                    if (condition.components[c])
                      {
                        agree = agree &&
                                data_gradient_mismatch(*condition.displacement,
                                                       c,
                                                       face->center(),
                                                       edge / h,
                                                       h)
                                  .empty();
                        reported =
                          reported || !data_gradient_mismatch(without_gradient,
                                                              c,
                                                              face->center(),
                                                              edge / h,
                                                              h)
                                         .empty();
                      }
                  n_agree += agree;
                  n_reported += reported;
                }
          }
      out << "body " << b << ": " << n_faces
          << " Dirichlet faces; gradient() agrees with the values on "
          << n_agree << "; without gradient() reported on " << n_reported
          << std::endl;
      AssertThrow(n_faces > 0 && n_agree == n_faces && n_reported == n_faces,
                  ExcMessage("data_gradient_mismatch: wrong verdict"));
    }

  const ConstantAlongVerticalLines constant_along;
  const Tensor<1, 2>               vertical({0., 1.});
  const std::string                along_line =
    data_gradient_mismatch(constant_along, 0, Point<2>(2., 1.), vertical, 0.1);
  const std::string across_line = data_gradient_mismatch(
    constant_along, 0, Point<2>(2., 1.), Tensor<1, 2>({1., 0.}), 0.1);
  out << "data constant along the face, zero gradient: "
      << (along_line.empty() ? "not reported" : "reported: " + along_line)
      << std::endl;
  out << "the same data across: " << across_line << std::endl;
  AssertThrow(along_line.empty() && !across_line.empty(),
              ExcMessage("data_gradient_mismatch: wrong verdict"));
}
