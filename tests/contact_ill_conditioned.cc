// A stiff, nearly incompressible body 1 on a soft one (blocks, E1/E2 = 1e3,
// nu = 0.499 on both, mu = 1.5; stability sweep case 118): the multipliers
// are differences of nodal forces about 1e6 times larger than themselves,
// so the complementarity residual cannot drop below about 1e-10 to 1e-9,
// near the default tolerance 1e-10 (which side depends on the BLAS and
// the rank count). With Contact/Tolerance = 0 the solver may stop only at
// that round-off floor: it must accept the converged sets there (it
// stopped with "the linear solver is not accurate enough" before), and the
// solution must still be right:
//  - contact force = applied load (1e-8 relative);
//  - every traction in the Coulomb cone and every slip node on its edge,
//    to the round-off floor times the largest pressure;
//  - open nodes carry no pressure.
// 1 and 2 ranks.

#include "contact_test_utilities.h"

#include <cmath>

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  auto settings = testing::stiff_slave_blocks("10", "4, 4", "8, 8");
  settings.insert(settings.end(),
                  {{"Mesh/Global refinements", "1"},
                   {"Contact/Friction coefficient", "1.5"},
                   {"Contact/Tolerance", "0"}});
  const auto   p  = testing::solve_contact(settings);
  const double mu = 1.5;

  AssertThrow(p->report.converged, ExcMessage("not converged"));
  const double residual = p->report.residual_history.back();
  AssertThrow(residual <= p->report.residual_round_off_floor,
              ExcMessage("converged above the reported round-off floor " +
                         std::to_string(p->report.residual_round_off_floor)));

  const Tensor<1, 2> applied({0., -10. * 100.});
  const double       imbalance =
    (p->report.contact_force + applied).norm() / applied.norm();
  AssertThrow(imbalance < 1e-8,
              ExcMessage("contact force off by " + std::to_string(imbalance)));

  // 1e-8 of the largest pressure: the floor here is ~1e-9.
  testing::assert_contact_conditions("case 118",
                                     p->solver->node_states(),
                                     mu,
                                     1e-8);

  out << "blocks, E1/E2 = 1e3, nu = 0.499, mu = 1.5: converged in "
      << p->report.newton_iterations << " Newton steps (" << p->report.n_stick
      << " stick, " << p->report.n_slip
      << " slip), Tolerance = 0, residual at the round-off floor: yes; "
         "contact force = load (1e-8): yes; tractions in the "
         "cone, slip nodes on its edge, open nodes free (1e-8 p_max): yes"
      << std::endl;
}
