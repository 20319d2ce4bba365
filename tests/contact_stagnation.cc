// A stiff, nearly incompressible body 1 on a coarse, soft, locking body 2
// (blocks, E1/E2 = 1e3, nu = 0.499, triangles, mesh ratio 1:8, mu = 0.3;
// the smallest variant of stability sweep case 259: upper 16x16, lower
// 2x2, one refinement). The multipliers of the fine slave side oscillate
// from node to node, the contact zone is fragmented, and one stick node
// holds body 1 tangentially. The full active set rule moves dozens of
// nodes per step that undo each other's changes, without an exact cycle;
// it stopped at step 11 with "would slide" (all active nodes slip). With
// restricted set changes on stagnation and the stick node kept, it must
// converge, and the solution must be right:
//  - contact force = applied load (1e-6 relative, the sweep's test: the
//    round-off of the nodal forces of 4225 nodes of a body with
//    E = 1.3e8 MPa leaves 9.4e-8 here; contact_ill_conditioned's 4x4
//    block reaches 1e-8);
//  - every traction in the Coulomb cone, slip nodes on its edge, open
//    nodes free, to 1e-8 of the largest pressure;
//  - the same sets, tractions and displacements from another iteration
//    path: c x 1e3 (which takes a different path).
// 1 rank.

#include "contact_test_utilities.h"

#include <cmath>

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const std::string b = "Scene/Blocks/";
  const std::vector<std::pair<std::string, std::string>> settings = {
    {"Scene/Name", "blocks"},
    {b + "Pressure", "10"},
    {b + "Upper body subdivisions", "16, 16"},
    {b + "Lower body subdivisions", "2, 2"},
    {b + "Hold centre line", "false"},
    {b + "Body 1/Young's modulus", "130000000"},
    {b + "Body 2/Young's modulus", "130000"},
    {b + "Body 1/Poisson's ratio", "0.499"},
    {b + "Body 2/Poisson's ratio", "0.499"},
    {"Mesh/Cell type", "triangle"},
    {"Mesh/Global refinements", "1"},
    {"Contact/Friction coefficient", "0.3"}};
  const double mu = 0.3;

  const auto p = testing::solve_contact(settings);
  AssertThrow(p->report.converged, ExcMessage("not converged"));
  const unsigned int n_steps = p->report.newton_iterations;

  const Tensor<1, 2> applied({0., -10. * 100.});
  const double       imbalance =
    (p->report.contact_force + applied).norm() / applied.norm();
  AssertThrow(imbalance < 1e-6,
              ExcMessage("contact force off by " + Utilities::to_string(imbalance)));

  double p_max = 0;
  for (const auto &s : p->solver->node_states())
    p_max = std::max(p_max, s.pressure);
  double worst_cone = 0, worst_edge = 0, worst_open = 0, worst_pressure = 0;
  for (const auto &s : p->solver->node_states())
    {
      if (s.status == ContactStatus::open)
        worst_open = std::max({worst_open,
                               std::abs(s.pressure),
                               std::abs(s.tangential_traction)});
      else
        {
          worst_pressure = std::max(worst_pressure, -s.pressure);
          worst_cone     = std::max(worst_cone,
                                std::abs(s.tangential_traction) -
                                  mu * s.pressure);
          if (s.status == ContactStatus::slip)
            worst_edge =
              std::max(worst_edge,
                       std::abs(s.tangential_traction -
                                mu * s.slip_sign * s.pressure));
        }
    }
  AssertThrow(worst_cone <= 1e-8 * p_max && worst_edge <= 1e-8 * p_max &&
                worst_open <= 1e-8 * p_max && worst_pressure <= 1e-8 * p_max,
              ExcMessage("contact conditions violated: cone " +
                         std::to_string(worst_cone / p_max) + ", edge " +
                         std::to_string(worst_edge / p_max) + ", open " +
                         std::to_string(worst_open / p_max) +
                         ", negative pressure " +
                         std::to_string(worst_pressure / p_max)));

  auto other_settings = settings;
  other_settings.emplace_back("Contact/Complementarity scale", "1000");
  const auto q = testing::solve_contact(other_settings);
  AssertThrow(q->report.converged, ExcMessage("c x 1e3: not converged"));
  testing::assert_same_contact_solution("c x 1e3", *p, *q);

  out << "blocks 16x16 on 2x2, triangles, E1/E2 = 1e3, nu = 0.499, mu = 0.3: "
         "converged: yes, in 10-40 Newton steps: "
      << (n_steps >= 10 && n_steps <= 40 ? "yes" : "no") << " ("
      << p->report.n_active << " active, " << p->report.n_stick
      << " stick, " << p->report.n_slip << " slip, p_max = "
      << std::setprecision(4) << p_max
      << " MPa); contact force = load (1e-6): yes; tractions in the cone, "
         "slip nodes on its edge, open nodes free (1e-8 p_max): yes; same "
         "solution with c x 1e3: yes"
      << std::endl;
}
