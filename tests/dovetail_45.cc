// The dovetail of prm/dovetail.prm with flanks at 45 degrees
// (prm/meshes/dovetail_45.geo; otherwise tests/dovetail's data: steel,
// omega = 1000 rad/s about an axis 300 mm below the root, mu = 0.5, P1
// triangles, the first mesh). tan 45 = 1 > mu: no node of a flank can
// stick, and the blade is held by the wedge of its two flanks alone, their
// normal forces opposing each other sideways. The contact solver's test of
// a floating body whose nodes all slip once refused this ("would slide");
// it now asks whether the normals of the slipping nodes leave a rigid
// motion free, and here they do not. Truths that need no finite elements:
//  - global equilibrium: the contact force on the blade is minus its
//    centrifugal force rho omega^2 A (x_c - x_axis), A and x_c in closed
//    form from the outline's corners (shoelace), to 1e-11 relative;
//  - all slip: every active node slips, none sticks, and its tangential
//    traction lies on the Coulomb cone, |lambda_t| = mu p (1e-12 of the
//    largest pressure);
//  - each flank's force in closed form: every node of a straight flank
//    slips the same way with lambda_t = mu p, so the flank's force on the
//    blade is N (-n) + mu N t_out with n = (sin a, cos a) the blade's
//    outer normal on the right flank and t_out = (cos a, -sin a) down the
//    flank (friction resists the blade's outward slip). The two flanks'
//    horizontal parts cancel (mirror images) and their vertical parts
//    carry F = |centrifugal force|: N = F / (2 (cos a + mu sin a)), the
//    right flank's force N (mu cos a - sin a, -(cos a + mu sin a)), to
//    1e-11 of F.
// The 2-rank output is the same file: 1 and 2 ranks agree.

#include "contact_test_utilities.h"
#include "dovetail_blade.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const double   rho = 7.85e-9, omega = 1000, mu = 0.5;
  const Point<2> axis(0, -300);
  const double   alpha = numbers::PI / 4;

  // The blade's outline (dovetail.geo with alpha = 45), its area and
  // centroid in closed form.
  const DovetailBlade blade(alpha);
  const double        A           = blade.area;
  const Point<2>      centroid    = blade.centroid;
  const Tensor<1, 2>  centrifugal = rho * omega * omega * A * (centroid - axis);
  const double        F           = centrifugal.norm();

  out << std::setprecision(8) << "blade: area " << A << " mm^2, centroid ("
      << (std::abs(centroid[0]) < 1e-12 ? 0. : centroid[0]) << ", "
      << centroid[1] << ") mm; centrifugal force (0, " << centrifugal[1]
      << ") N/mm" << std::endl;

  auto problem = testing::solve_example("dovetail.prm", "dovetail_45.geo");
  const ContactSolverReport &report = problem->report;
  const double equilibrium = (report.contact_force + centrifugal).norm() / F;
  out << "contact force on the blade (" << std::setprecision(8)
      << (std::abs(report.contact_force[0]) < 1e-10 * F ?
            0. :
            report.contact_force[0])
      << ", " << report.contact_force[1]
      << ") N/mm: minus the centrifugal force to 1e-11: "
      << (equilibrium < 1e-11 ? "yes" : "no")
      << "; Newton steps: " << report.newton_iterations << std::endl;
  AssertThrow(equilibrium < 1e-11,
              ExcMessage("equilibrium off by " + std::to_string(equilibrium)));
  // 3 measured; 8 when a node was kept in stick against the all-slip sets.
  AssertThrow(report.newton_iterations <= 5,
              ExcMessage("Newton steps: " +
                         std::to_string(report.newton_iterations)));

  // Per flank (x < 0 left, x > 0 right): counts, force, the cone.
  const auto                 &states       = problem->solver->node_states();
  const double                p_max        = report.max_contact_pressure;
  double                      slip_on_cone = 0;
  std::array<unsigned int, 2> n_stick{{0, 0}}, n_slip{{0, 0}}, n_open{{0, 0}};
  std::array<Tensor<1, 2>, 2> flank_force;
  for (const auto &s : states)
    {
      const unsigned int side = s.position[0] > 0;
      n_stick[side] += s.status == ContactStatus::stick;
      n_slip[side] += s.status == ContactStatus::slip;
      n_open[side] += s.status == ContactStatus::open;
      flank_force[side] +=
        -s.weight * (s.pressure * s.normal + s.tangential_traction * s.tangent);
      if (s.status == ContactStatus::slip)
        slip_on_cone =
          std::max(slip_on_cone,
                   std::abs(std::abs(s.tangential_traction) - mu * s.pressure) /
                     p_max);
    }

  // The closed form: the right flank's force, the left one's its mirror.
  const double       N = F / (2 * (std::cos(alpha) + mu * std::sin(alpha)));
  const Tensor<1, 2> right({N * (mu * std::cos(alpha) - std::sin(alpha)),
                            -N * (std::cos(alpha) + mu * std::sin(alpha))});
  const Tensor<1, 2> left({-right[0], right[1]});
  const double       flank_error =
    std::max((flank_force[1] - right).norm(), (flank_force[0] - left).norm()) /
    F;

  out << states.size() << " slave nodes, largest pressure "
      << std::setprecision(4) << p_max << " MPa" << std::endl;
  for (unsigned int side : {0, 1})
    out << (side == 0 ? "left " : "right") << " flank: " << n_stick[side]
        << " stick, " << n_slip[side] << " slip, " << n_open[side]
        << " open; force on the blade (" << std::setprecision(8)
        << flank_force[side][0] << ", " << flank_force[side][1] << ") N/mm"
        << std::endl;
  out << "closed form N = F / (2 (cos a + mu sin a)) = " << N
      << " N/mm, right flank (" << right[0] << ", " << right[1]
      << ") N/mm; both flanks to 1e-11 F: "
      << (flank_error < 1e-11 ? "yes" : "no") << std::endl
      << "slip nodes on the cone |lambda_t| = mu p to 1e-12 p_max: "
      << (slip_on_cone < 1e-12 ? "yes" : "no") << std::endl;

  for (unsigned int side : {0, 1})
    AssertThrow(n_stick[side] == 0 && n_slip[side] > 0,
                ExcMessage("a flank has stick nodes, or no slip node"));
  AssertThrow(slip_on_cone < 1e-12,
              ExcMessage("slip nodes off the cone by " +
                         std::to_string(slip_on_cone)));
  AssertThrow(flank_error < 1e-11,
              ExcMessage("flank forces off the closed form by " +
                         std::to_string(flank_error) + " F"));
}
