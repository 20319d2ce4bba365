// Contact patch test (theory.md section 6) on non-matching meshes (3 upper
// vs 10 lower cells across the interface, ratio 1:3.3), Q1, P1, Q2, P2:
//  - same material, mu = 0 and mu = 0.3: the contact pressure equals the
//    applied pressure p at every slave node (1e-8 relative);
//  - mu = 0.3 and different nu on the two bodies (the upper block then
//    held by friction alone): equilibrium, contact force = applied load
//    (1e-8 relative).

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  const double                     p = 2.5, width = 10;

  for (const std::string degree : {"1", "2"})
    for (const std::string cell_type : {"quadrilateral", "triangle"})
      for (const std::string mu : {"0", "0.3"})
        {
          const auto problem = testing::solve_contact(
            {{"Scene/Name", "patch"},
             {"Mesh/Cell type", cell_type},
             {"Finite elements/Polynomial degree", degree},
             {"Scene/Patch/Pressure", "2.5"},
             {"Scene/Patch/Upper body subdivisions", "3, 2"},
             {"Scene/Patch/Lower body subdivisions", "10, 4"},
             {"Contact/Friction coefficient", mu}});
          double worst = 0;
          for (const auto &s : problem->solver->node_states())
            worst = std::max(worst, std::abs(s.pressure - p) / p);
          out << "patch, degree " << degree << ", " << cell_type
              << ", mu = " << mu << ": "
              << problem->solver->node_states().size()
              << " slave nodes, all active: "
              << (problem->report.n_active ==
                      problem->solver->node_states().size() ?
                    "yes" :
                    "no")
              << ", pressure = p to 1e-8: " << (worst < 1e-8 ? "yes" : "no")
              << std::endl;
          AssertThrow(worst < 1e-8,
                      ExcMessage("pressure error " + std::to_string(worst)));
        }

  for (const std::string cell_type : {"quadrilateral", "triangle"})
    {
      const auto problem = testing::solve_contact(
        {{"Scene/Name", "patch"},
         {"Mesh/Cell type", cell_type},
         {"Scene/Patch/Pressure", "2.5"},
         {"Scene/Patch/Hold upper body", "false"},
         {"Scene/Patch/Body 1/Poisson's ratio", "0.4"},
         {"Scene/Patch/Body 2/Poisson's ratio", "0.1"},
         {"Scene/Patch/Upper body subdivisions", "3, 2"},
         {"Scene/Patch/Lower body subdivisions", "10, 4"},
         {"Contact/Friction coefficient", "0.3"}});
      const Tensor<1, 2> applied({0., -p * width});
      const double       imbalance =
        (problem->report.contact_force + applied).norm() / applied.norm();
      out << "patch, " << cell_type
          << ", mu = 0.3, nu = 0.4 on 0.1: contact force = applied load to "
             "1e-8: "
          << (imbalance < 1e-8 ? "yes" : "no") << " ("
          << problem->report.n_stick << " stick, " << problem->report.n_slip
          << " slip nodes)" << std::endl;
      AssertThrow(imbalance < 1e-8,
                  ExcMessage("imbalance " + std::to_string(imbalance)));
    }
}
