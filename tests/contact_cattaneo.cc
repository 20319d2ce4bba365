// Cattaneo-Mindlin (theory.md section 6): the Hertz geometry, identical
// materials, mu = 0.3, the disc pushed down and then moved sideways in 5
// quasi-static steps by a rigid holder. With P' and Q the normal and
// tangential contact force, the stick zone is |x| < c = a sqrt(1 - Q /
// (mu P')): the computed c (midway between the outermost stick node and
// the first slip node) must be within 5 % of it; the tangential traction
// is compared with q(x) = mu p0 / a [sqrt(a^2 - x^2) - sqrt(c^2 - x^2)]
// (|x| < c), mu p0 / a sqrt(a^2 - x^2) (c <= |x| <= a) in the L2 sense.

#include <coulomb_adapt/scenes/hertz.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  ParameterHandler prm;
  const Parameters parameters =
    testing::make_parameters(prm, {{"Scene/Name", "cattaneo"}});
  const auto scene = scenes::create_scene(parameters, prm);
  std::array<std::unique_ptr<ElasticBody>, 2> bodies;
  for (unsigned int b = 0; b < 2; ++b)
    bodies[b] = std::make_unique<ElasticBody>(MPI_COMM_WORLD,
                                              *scene,
                                              b,
                                              parameters.mesh.cell_type,
                                              0,
                                              parameters.finite_elements);
  ConditionalOStream  quiet(std::cout, false);
  ContactSolver       solver(*bodies[0],
                       *bodies[1],
                       parameters.contact,
                       parameters.linear_solver,
                       quiet);
  ContactSolverReport report;
  for (unsigned int step = 1; step <= scene->n_load_steps(); ++step)
    {
      scene->set_load_step(step);
      for (auto &body : bodies)
        {
          body->setup_system();
          body->assemble_system();
        }
      report = solver.solve();
    }

  const double mu = parameters.contact.friction_coefficient;
  const double P = report.contact_force[1], Q = -report.contact_force[0];
  // Hertz's a for the measured P' (a grows with sqrt(P')).
  const auto  &hertz = dynamic_cast<const scenes::Hertz &>(*scene);
  const double a     = hertz.contact_half_width() * std::sqrt(P / 1000.);
  const double p0    = 2 * P / (numbers::PI * a);
  const double c     = a * std::sqrt(1 - Q / (mu * P));

  const auto &states     = solver.node_states();
  double      stick_edge = 0;
  for (unsigned int j = 0; j + 1 < states.size(); ++j)
    for (const int d : {0, 1})
      {
        const auto &inner = states[j + d], &outer = states[j + 1 - d];
        if (inner.status == ContactStatus::stick &&
            outer.status != ContactStatus::stick)
          stick_edge = std::max(stick_edge,
                                0.5 * (std::abs(inner.position[0]) +
                                       std::abs(outer.position[0])));
      }
  double error2 = 0, norm2 = 0;
  for (const auto &s : states)
    {
      const double x = std::abs(s.position[0]);
      double       q = 0;
      if (x < a)
        q =
          mu * p0 / a *
          (std::sqrt(a * a - x * x) - (x < c ? std::sqrt(c * c - x * x) : 0.));
      error2 += s.weight * std::pow(s.tangential_traction - q, 2);
      norm2 += s.weight * q * q;
    }
  const double stick_error = std::abs(stick_edge - c) / c;
  const double l2_error    = std::sqrt(error2 / norm2);

  out << "cattaneo: Q / (mu P') between 0.3 and 0.9: "
      << (Q / (mu * P) > 0.3 && Q / (mu * P) < 0.9 ? "yes" : "no") << std::endl
      << "  stick zone half-width within 5 % of a sqrt(1 - Q / (mu P')): "
      << (stick_error < 0.05 ? "yes" : "no") << std::endl
      << "  relative L2 error of the tangential traction below 10 %: "
      << (l2_error < 0.10 ? "yes" : "no") << std::endl;
  out << std::setprecision(2) << "  P' = " << P << " N/mm, Q = " << Q
      << " N/mm, c_h / c = " << stick_edge / c
      << ", L2 error of q = " << l2_error << std::endl;
  AssertThrow(stick_error < 0.05 && l2_error < 0.10,
              ExcMessage("Cattaneo: stick zone error " +
                         std::to_string(stick_error) + ", traction error " +
                         std::to_string(l2_error)));
}
