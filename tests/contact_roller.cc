// A roller on a slave contact node, with friction: the seed's blocks
// (prm/blocks_gmsh.prm: the built-in scene's structured quadrilaterals,
// one global refinement, mu = 0.3, stick in the middle and slip at the
// ends) are symmetric about x = 100, and the right half
// (tests/data/blocks_half.geo, the same vertices there) with u_x = 0 on
// the symmetry line of both bodies must give the same solution. The
// symmetry line ends on the upper block's contact surface: the slave node
// (100, 200) has its x component, along the surface, fixed. That
// condition replaces the node's tangential contact condition (it sticks
// by construction, lambda_t = 0 there: the roller takes the tangential
// reaction) and its normal condition stays.
//
// Checked, node by node against the whole model (nodes at the same
// positions): the sets, pressures, tangential tractions, gaps and slips,
// to 1e-9 of the largest pressure and of the largest gap or slip (the
// direct solver; 1e-7 with the Krylov + AMG solver, whose Newton system
// eliminates the contact conditions, to its tolerance); the whole model's
// centre node has no tangential traction (round-off) and the half
// model's roller node reports none; each body's strain energy is half the
// whole model's, the vertical contact force half the load (force balance:
// the half's body 1 carries p times its width 50 mm), and its horizontal
// contact force is what the friction transmits, balanced by the roller.

#include <coulomb_adapt/indicator/exact_error.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const auto  whole = testing::solve_example("blocks_gmsh.prm",
                                            "blocks_structured.geo",
                                            {{"Mesh/Global refinements", "1"}});
  const auto &w     = whole->solver->node_states();
  double      p_max = 0, u_max = 0, centre_traction = 0;
  for (const auto &s : w)
    {
      p_max = std::max(p_max, s.pressure);
      u_max = std::max({u_max, std::abs(s.gap), std::abs(s.slip)});
      if (std::abs(s.position[0] - 100) < 1e-6)
        centre_traction = std::abs(s.tangential_traction);
    }
  out << "Whole model: " << w.size() << " slave nodes, "
      << whole->report.n_stick << " stick, " << whole->report.n_slip
      << " slip; vertical contact force " << std::setprecision(8)
      << whole->report.contact_force[1] << " N/mm, horizontal "
      << (std::abs(whole->report.contact_force[0]) < 1e-10 * 1000 ? "0" :
                                                                    "not 0")
      << " (1e-10 of the load); tangential traction at "
      << "x = 100: " << (centre_traction / p_max < 1e-10 ? "0" : "not 0")
      << " (1e-10 of the largest pressure)" << std::endl;
  AssertThrow(centre_traction / p_max < 1e-10,
              ExcMessage("the whole model is not symmetric"));
  double whole_energy[2];
  for (unsigned int k = 0; k < 2; ++k)
    whole_energy[k] =
      strain_energy(*whole->bodies[k], whole->bodies[k]->solution());

  for (const std::string solver : {"direct", "amg"})
    {
      const double tolerance = solver == "direct" ? 1e-9 : 1e-7;
      const auto   half      = testing::solve_contact(
        {{"Scene/Gmsh/Mesh file",
                 testing::repository_root() + "/tests/data/blocks_half.geo"},
                {"Scene/Gmsh/Fixed components", "base: x y, symmetry line: x"},
                {"Mesh/Global refinements", "1"},
                {"Linear solver/Type", solver}},
        testing::example_file("blocks_gmsh.prm"));
      const auto  &h        = half->solver->node_states();
      double       traction = 0, kinematics = 0, roller_traction = 0;
      unsigned int n_same = 0, n_rollers = 0;
      for (const auto &s : h)
        {
          const ContactNodeState *match = nullptr;
          for (const auto &t : w)
            if (t.position.distance(s.position) < 1e-6)
              match = &t;
          AssertThrow(match != nullptr,
                      ExcMessage("a node of the half model is not a node of "
                                 "the whole one"));
          n_same += s.status == match->status;
          traction = std::max(
            {traction,
             std::abs(s.pressure - match->pressure),
             std::abs(s.tangential_traction - match->tangential_traction)});
          kinematics = std::max({kinematics,
                                 std::abs(s.gap - match->gap),
                                 std::abs(s.slip - match->slip)});
          if (s.held_tangentially)
            {
              ++n_rollers;
              roller_traction = std::abs(s.tangential_traction);
            }
        }
      double energy = 0;
      for (unsigned int k = 0; k < 2; ++k)
        energy =
          std::max(energy,
                   std::abs(2 *
                              strain_energy(*half->bodies[k],
                                            half->bodies[k]->solution()) /
                              whole_energy[k] -
                            1));
      const Tensor<1, 2> force = half->report.contact_force;
      const double       load  = 10 * 50; // p times the half's width
      const double       balance =
        std::abs(2 * force[1] - whole->report.contact_force[1]) / load +
        std::abs(force[1] - load) / load;
      const double difference =
        std::max({traction / p_max, kinematics / u_max, energy, balance});

      out << "Half model, " << solver << " solver: " << h.size()
          << " slave nodes, " << n_same << " in the whole model's state, "
          << n_rollers << " with a roller (tangential traction / p "
          << (roller_traction < 1e-12 * p_max ? "below 1e-12" : "ABOVE") << ")"
          << std::endl
          << "  contact force (" << std::setprecision(5) << force[0] << ", "
          << std::setprecision(8) << force[1]
          << ") N/mm; largest difference from the whole model "
          << (difference < tolerance ? "below " : "ABOVE ") << tolerance
          << std::endl;
      AssertThrow(n_same == h.size() && n_rollers == 1 &&
                    roller_traction < 1e-12 * p_max,
                  ExcMessage("the sets or the roller differ"));
      AssertThrow(difference < tolerance,
                  ExcMessage("the half model differs from the whole one by " +
                             std::to_string(difference)));
      // The friction the half transmits, against the whole model's
      // tangential tractions on x > 100.
      double friction = 0;
      for (const auto &t : w)
        if (t.position[0] > 100 + 1e-6)
          friction -= t.weight * t.tangential_traction * t.tangent[0];
      AssertThrow(std::abs(force[0] - friction) < tolerance * load,
                  ExcMessage("horizontal contact force " +
                             std::to_string(force[0]) + ", expected " +
                             std::to_string(friction)));
    }
}
