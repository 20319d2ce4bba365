// Friction limits (theory.md section 6): a block pushed sideways by Q
//  - Q < mu N (patch, shear 0.1 MPa under 1 MPa, mu = 0.3): it sticks, and
//    the tangential contact force balances Q (1e-8);
//  - Q > mu N under force control (shear 0.5 MPa): no static equilibrium;
//    the solver stops with the diagnosis that the block slides;
//  - beyond the limit under displacement control (cattaneo, holder moved
//    far sideways): every active node slips with |lambda_t| = mu lambda_n
//    (1e-8), and so do the resultants, sum D lambda_t = mu sum D lambda_n.

#include <coulomb_adapt/core/parameter_error.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  {
    const auto problem =
      testing::solve_contact({{"Scene/Name", "patch"},
                              {"Scene/Patch/Shear traction", "0.1"},
                              {"Scene/Patch/Hold upper body", "false"}});
    const double Q         = 0.1 * 10;
    const double imbalance = std::abs(problem->report.contact_force[0] + Q) / Q;
    out << "Q = 0.33 mu N: converged, all " << problem->report.n_active
        << " active nodes stick: "
        << (problem->report.n_stick == problem->report.n_active ? "yes" : "no")
        << ", tangential force = Q to 1e-8: "
        << (imbalance < 1e-8 ? "yes" : "no") << std::endl;
    AssertThrow(problem->report.n_stick == problem->report.n_active &&
                  imbalance < 1e-8,
                ExcMessage("sticking block"));
  }

  {
    std::string message;
    try
      {
        testing::solve_contact({{"Scene/Name", "patch"},
                                {"Scene/Patch/Shear traction", "0.5"},
                                {"Scene/Patch/Hold upper body", "false"}});
      }
    catch (const std::exception &e)
      {
        message = user_message(e);
      }
    const bool diagnosed =
      message.find("would slide: in the contact sets of this step every "
                   "active node slips") != std::string::npos;
    out << "Q = 1.67 mu N under force control: stopped with the sliding "
           "diagnosis: "
        << (diagnosed ? "yes" : "no") << std::endl;
    AssertThrow(diagnosed, ExcMessage("no sliding diagnosis: " + message));
  }

  {
    const auto problem = testing::solve_contact(
      {{"Scene/Name", "cattaneo"},
       {"Scene/Cattaneo/Tangential displacement", "0.05"},
       {"Scene/Cattaneo/Tangential load steps", "2"}});
    // solve_contact does one load step; run the rest of the path.
    auto &p = *problem;
    for (unsigned int step = 2; step <= p.scene->n_load_steps(); ++step)
      {
        p.scene->set_load_step(step);
        for (auto &body : p.bodies)
          {
            body->setup_system();
            body->assemble_system();
          }
        p.report = p.solver->solve();
      }
    const double mu    = 0.3;
    double       p_max = 0, worst = 0;
    for (const auto &s : p.solver->node_states())
      p_max = std::max(p_max, s.pressure);
    for (const auto &s : p.solver->node_states())
      if (s.status != ContactStatus::open)
        worst =
          std::max(worst,
                   std::abs(std::abs(s.tangential_traction) - mu * s.pressure));
    // Resultants along the nodal normals and tangents (on the curved disc
    // the x and y components mix them).
    double P = 0, Q = 0;
    for (const auto &s : p.solver->node_states())
      {
        P += s.weight * s.pressure;
        Q += s.weight * s.tangential_traction;
      }
    out << "displacement control beyond the limit: all " << p.report.n_active
        << " active nodes slip: "
        << (p.report.n_slip == p.report.n_active ? "yes" : "no")
        << ", |lambda_t| = mu lambda_n to 1e-8: "
        << (worst < 1e-8 * p_max ? "yes" : "no")
        << ", sum D lambda_t = mu sum D lambda_n to 1e-8: "
        << (std::abs(Q - mu * P) < 1e-8 * P ? "yes" : "no") << std::endl;
    AssertThrow(p.report.n_slip == p.report.n_active && worst < 1e-8 * p_max &&
                  std::abs(Q - mu * P) < 1e-8 * P,
                ExcMessage("full slip"));
  }
}
