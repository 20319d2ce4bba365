// solve_symmetric_positive_definite (solvers/symmetric_direct_solver.h):
// MUMPS's LDL^T of the lower triangle, the CRE estimator's parameters'
// system (Estimator = cre). Checked on the SPD system of a P2 reaction-
// diffusion problem on a distributed mesh (a few thousand unknowns, split
// between the ranks of a 2-rank run), against what must hold for any
// correct solve:
//
// - the backward error |A x - b| / (|A|_F |x|) is round-off (1e-16);
// - x agrees with MUMPS's LU of the whole matrix through Amesos (the
//   solver it replaced) to 1e-12 relative, so the lower triangle is read
//   and the unknowns are gathered and scattered back in the right order;
// - the solve is linear in b: b * 1000 gives x * 1000 to 1e-14 relative
//   (the factorisation does not depend on b; the CRE estimate's
//   homogeneity test rests on it);
// - a matrix that is singular (a zero row and column) is reported with
//   MUMPS's error code, on every rank, not returned as a solution.

#include <deal.II/lac/trilinos_solver.h>

#include <coulomb_adapt/solvers/symmetric_direct_solver.h>

#include "reaction_diffusion_system.h"
#include "test_utilities.h"

#include <cmath>
#include <string>

using namespace coulomb_adapt;

namespace
{
  using System = testing::ReactionDiffusionSystem;
  using testing::relative_difference;

  double
  relative_residual(const System                        &system,
                    const TrilinosWrappers::MPI::Vector &x)
  {
    TrilinosWrappers::MPI::Vector residual(system.b);
    system.A.vmult(residual, x);
    residual -= system.b;
    return residual.l2_norm() / (system.A.frobenius_norm() * x.l2_norm());
  }



} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  System system = testing::reaction_diffusion_system(comm);
  TrilinosWrappers::MPI::Vector x(system.b);
  solve_symmetric_positive_definite(system.A, x, system.b);
  out << "unknowns: " << system.A.m() << std::endl;
  const double residual = relative_residual(system, x);
  out << "backward error |A x - b| / (|A|_F |x|) below 1e-16: "
      << (residual < 1e-16 ? "yes" : "no") << std::endl;

  TrilinosWrappers::MPI::Vector                  x_lu(system.b);
  SolverControl                                  control(1, 0);
  TrilinosWrappers::SolverDirect::AdditionalData data(false, "Amesos_Mumps");
  TrilinosWrappers::SolverDirect                 lu(control, data);
  lu.initialize(system.A);
  lu.solve(x_lu, system.b);
  const double difference = relative_difference(x, x_lu);
  out << "agrees with Amesos' LU to 1e-12: "
      << (difference < 1e-12 ? "yes" : "no") << std::endl;

  TrilinosWrappers::MPI::Vector b_scaled(system.b), x_scaled(system.b);
  b_scaled *= 1000.;
  solve_symmetric_positive_definite(system.A, x_scaled, b_scaled);
  x_scaled /= 1000.;
  const double scaling = relative_difference(x_scaled, x);
  out << "b * 1000 gives x * 1000 to 1e-14: "
      << (scaling < 1e-14 ? "yes" : "no") << std::endl;

  // Singular: the first row and column set to zero.
  const types::global_dof_index first = 0;
  if (system.A.in_local_range(first))
    for (auto entry = system.A.begin(first); entry != system.A.end(first);
         ++entry)
      entry->value() = 0;
  for (const auto i : system.A.locally_owned_range_indices())
    if (system.A.el(i, first) != 0)
      system.A.set(i, first, 0.);
  system.A.compress(VectorOperation::insert);
  try
    {
      solve_symmetric_positive_definite(system.A, x, system.b);
      out << "singular matrix: no error" << std::endl;
    }
  catch (const std::exception &error)
    {
      // deal.II wraps the message's lines: join them.
      std::string message;
      for (const char c : std::string(error.what()))
        if (c != '\n' &&
            !(c == ' ' && !message.empty() && message.back() == ' '))
          message += c;
      out << "singular matrix: INFOG(1) = -10 reported: "
          << (message.find("INFOG(1) = -10,") != std::string::npos ? "yes" :
                                                                     "no")
          << ", 'numerically singular' said: "
          << (message.find("the matrix is numerically singular") !=
                  std::string::npos ?
                "yes" :
                "no")
          << std::endl;
    }

  AssertThrow(residual < 1e-13,
              ExcMessage("residual " + std::to_string(residual)));
  AssertThrow(difference < 1e-12,
              ExcMessage("difference to LU " + std::to_string(difference)));
  AssertThrow(scaling < 1e-14,
              ExcMessage("scaling " + std::to_string(scaling)));
}
