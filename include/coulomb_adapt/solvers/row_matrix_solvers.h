#ifndef coulomb_adapt_solvers_row_matrix_solvers_h
#define coulomb_adapt_solvers_row_matrix_solvers_h

#include <coulomb_adapt/solvers/linear_solver.h>

#include <Epetra_Operator.h>
#include <Epetra_RowMatrix.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * The solvers of linear_solver.h for a matrix that is not stored as a
   * deal.II matrix but given by its rows and its product (ReducedMatrix,
   * the eliminated contact system's A read from the bodies' K). The
   * same settings, so the same hierarchy and iterates for the same
   * entries.
   */

  /** ElasticityAMG::initialize() for @p A given by its rows. */
  void
  initialize_elasticity_amg(
    ElasticityAMG                              &amg,
    const Epetra_RowMatrix                     &A,
    const std::vector<std::vector<double>>     &near_null_space,
    const std::vector<types::global_dof_index> &zero_rows);

  /** solve_krylov() for @p A given by its product. */
  LinearSolverReport
  solve_krylov(const Epetra_Operator                    &A,
               TrilinosWrappers::MPI::Vector            &x,
               const TrilinosWrappers::MPI::Vector      &b,
               const TrilinosWrappers::PreconditionBase &preconditioner,
               const parameters::LinearSolver           &settings,
               const bool                                symmetric);
} // namespace coulomb_adapt

#endif
