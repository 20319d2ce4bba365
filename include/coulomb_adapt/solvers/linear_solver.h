#ifndef coulomb_adapt_solvers_linear_solver_h
#define coulomb_adapt_solvers_linear_solver_h

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/core/parameters.h>

#include <string>
#include <vector>

class Epetra_Operator;
class Epetra_RowMatrix;

namespace coulomb_adapt
{
  /** What a linear solve did, for the log and summary.json. */
  struct LinearSolverReport
  {
    /** "direct (Amesos_Mumps)", "cg+amg" or "gmres+amg". */
    std::string  method;
    unsigned int n_iterations = 0;
    /** The AMG hierarchy of an earlier matrix was reused
     * (EliminatedContactSystem). */
    bool preconditioner_reused = false;
  };

  /**
   * Solve A x = b: symmetric positive definite (elasticity, the
   * frictionless eliminated contact system) or, with @p symmetric false,
   * a non-symmetric one (the frictional eliminated contact system, a
   * pinned floating body, or the row-replacing contact system, which
   * only the direct solver takes).
   *
   * Small systems go to a sparse direct solver (Trilinos Amesos, which
   * gathers the matrix in parallel); large ones to CG (GMRES if not
   * symmetric) preconditioned by ML smoothed-aggregation algebraic
   * multigrid, whose near null space is given the rigid body modes of
   * elasticity (@p near_null_space, one vector of locally owned values per
   * mode): with only the translations, aggregation-based AMG converges
   * much more slowly on elasticity.
   *
   * Failure to converge throws with the residual reached.
   */
  LinearSolverReport
  solve_linear_system(const TrilinosWrappers::SparseMatrix   &A,
                      TrilinosWrappers::MPI::Vector          &x,
                      const TrilinosWrappers::MPI::Vector    &b,
                      const std::vector<std::vector<double>> &near_null_space,
                      const parameters::LinearSolver         &settings,
                      const bool                              symmetric = true);

  /**
   * The message for a Krylov solve of @p system (e.g. "body 'upper
   * square'") that stopped at 'Linear solver/Maximum iterations' after
   * @p last_step iterations at @p last_residual: deal.II's own text names
   * neither the system nor the parameter. @p solver_name, if not empty,
   * follows "the iterative linear solver" in parentheses.
   */
  std::string
  iteration_limit_message(const std::string &system,
                          const std::string &solver_name,
                          const unsigned int last_step,
                          const double       last_residual);

  /**
   * ML smoothed-aggregation AMG for elasticity-like systems, with the
   * given near null space (rigid body modes, one vector of locally owned
   * values per mode) and two unknowns per node. Kept as an object so that
   * a caller can reuse one hierarchy for several solves (the Newton steps
   * of a contact solve, EliminatedContactSystem).
   */
  struct ElasticityAMG
  {
    /** @p zero_rows: locally owned rows of @p A at which the modes are
     * taken as zero (the decoupled rows of an eliminated system), so that
     * a caller need not copy the modes to change them. */
    void
    initialize(const TrilinosWrappers::SparseMatrix       &A,
               const std::vector<std::vector<double>>     &near_null_space,
               const std::vector<types::global_dof_index> &zero_rows = {});

    TrilinosWrappers::PreconditionAMG preconditioner;
  };

  /**
   * Give the pages of freed heap memory back to the system (glibc's
   * malloc_trim; nothing elsewhere). The AMG setup, the Krylov basis and
   * the sparsity pattern of a reduced matrix free hundreds of MiB in many
   * small blocks, which the heap otherwise keeps resident: the next
   * allocations do not fit in them and grow the process instead
   * (benchmarks/adaptive_run, "Memory").
   */
  void
  return_freed_heap_memory();

  /**
   * CG (@p symmetric) or right-preconditioned GMRES(100) on A x = b to
   * settings.relative_tolerance times |b|, starting from the given @p x.
   * Failure to converge throws SolverControl::NoConvergence.
   */
  LinearSolverReport
  solve_krylov(const TrilinosWrappers::SparseMatrix     &A,
               TrilinosWrappers::MPI::Vector            &x,
               const TrilinosWrappers::MPI::Vector      &b,
               const TrilinosWrappers::PreconditionBase &preconditioner,
               const parameters::LinearSolver           &settings,
               const bool                                symmetric);

  /* The same solvers for a matrix that is not stored as a deal.II matrix
   * but given by its rows and its product (ReducedMatrix, the eliminated
   * contact system's A read from the bodies' K): the same settings, so
   * the same hierarchy and iterates for the same entries. */

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
