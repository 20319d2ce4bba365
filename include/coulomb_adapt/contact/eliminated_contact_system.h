#ifndef coulomb_adapt_contact_eliminated_contact_system_h
#define coulomb_adapt_contact_eliminated_contact_system_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/contact/condensed_newton_system.h>
#include <coulomb_adapt/contact/eliminated_operator.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <array>
#include <memory>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The Newton system of one active-set step with the contact conditions
   * eliminated, for Krylov + AMG solves (doc/contact.md section 2, "Linear
   * solvers").
   *
   * The row-replacing system that the direct solver takes puts gap rows
   * (scaled D and M entries) and traction rows in place of the slave rows
   * of K; algebraic multigrid sees no elliptic operator there and GMRES
   * needed hundreds of iterations. Here the same discrete problem is
   * written on the null space of the constraints, as Dirichlet data are:
   *
   *   u = Z u~ + u_g,   (Z~^T K Z) u~ = Z~^T (f - K u_g),
   *
   * K = diag(K^1, K^2) the bodies' stiffness, f their loads. Z eliminates
   * at every active slave node j the constrained displacement components
   * in favour of the node's free component and the master displacements
   * (the dual basis makes D diagonal, so u^1_j is explicit):
   * n . (D_jj u^1_j - sum_l M_jl u^2_l) = g~_j, and at stick nodes also
   * t . (...) = the weighted slip of the previous load step. Z~ spans the
   * test functions that do no work against the contact traction: for a
   * frictionless or stick node Z~ = Z, so frictionless problems give a
   * symmetric positive definite matrix (elasticity of the two bodies tied
   * normally); at a slip node the traction lies along
   * n + mu s t, not n, which makes the matrix non-symmetric in those rows
   * only. Open nodes keep their rows (lambda_j = 0).
   *
   * The solution is that of the row-replacing system (tested to 1e-8 in
   * contact_linear_solvers); the multipliers follow from f^1 - K^1 u^1 as
   * before. Eliminated rows get K's diagonal entry and a zero right hand
   * side.
   */
  class EliminatedContactSystem : public CondensedNewtonSystem
  {
  public:
    /**
     * Take K^1, K^2 and f^1, f^2 of the bodies and the combined index
     * space of @p condensation (body 2 shifted); once per mesh and load
     * step. The bodies' systems are read, not copied: they must stay as
     * they are until the next reinit().
     */
    void
    reinit(const MortarInterface   &mortar,
           const ElasticBody       &slave,
           const ElasticBody       &master,
           const SlaveCondensation &condensation) override;

    /**
     * Build the eliminated rows of Z, Z~, u_g and, from them and the
     * bodies' K and f, the reduced system (EliminatedOperator) for the
     * sets given by @p nodes (the slave nodes this rank owns); once per
     * Newton step, nothing when neither the sets nor the gaps changed
     * since the last call.
     */
    void
    assemble(const std::vector<SlaveNodeConditions> &nodes) override;

    /**
     * Solve the reduced system; @p solution receives u (combined index
     * space, owned entries).
     *
     * Consecutive Newton steps differ only in the rows of the slave nodes
     * that changed set, so the Krylov solve starts from the previous
     * step's u, and the AMG hierarchy of an earlier step is reused when
     * at most max_changed_nodes_for_reuse slave nodes changed set since
     * it was built and its last solve needed at most 1.5 x + 5 the
     * iterations of the first (doc/contact.md section 2). The tolerance
     * is that of a fresh solve: only the cost changes, not the accuracy.
     */
    LinearSolverReport
    solve(const std::vector<std::vector<double>> &near_null_space,
          const parameters::LinearSolver         &settings,
          TrilinosWrappers::MPI::Vector          &solution) override;

  private:
    /** The Krylov solve's start: the last u on the components that stay
     * unknowns, zero at the eliminated ones (and before the first solve
     * on this mesh). */
    TrilinosWrappers::MPI::Vector
    initial_reduced_guess() const;
    /** Whether the current AMG hierarchy may serve this solve: few slave
     * nodes changed set since it was built (the same on every rank), and
     * its last solve needed few iterations. */
    bool
    hierarchy_may_be_reused() const;
    /** The reduced system solved with the current hierarchy, the
     * iterations capped; throws SolverControl::NoConvergence past the
     * cap. */
    LinearSolverReport
    solve_with_current_hierarchy(
      const parameters::LinearSolver &settings,
      TrilinosWrappers::MPI::Vector  &reduced_solution);
    /** A new hierarchy built for the reduced operator, and the reduced
     * system solved from @p initial_guess with it. */
    LinearSolverReport
    solve_with_fresh_hierarchy(
      const std::vector<std::vector<double>> &near_null_space,
      const parameters::LinearSolver         &settings,
      const TrilinosWrappers::MPI::Vector    &initial_guess,
      TrilinosWrappers::MPI::Vector          &reduced_solution);

    IndexSet                owned;
    MPI_Comm                communicator;
    types::global_dof_index offset = 0;
    /** The bodies' K and f (EliminatedOperator reads them row by row). */
    const TrilinosWrappers::SparseMatrix *K1 = nullptr;
    const TrilinosWrappers::SparseMatrix *K2 = nullptr;
    const TrilinosWrappers::MPI::Vector  *f1 = nullptr;
    const TrilinosWrappers::MPI::Vector  *f2 = nullptr;

    /** The rows of Z, Z~ and u_g of this step's eliminated components
     * that this rank owns; the identity (and zero) elsewhere. */
    EliminatedRows eliminated;
    /** A, its rows away from the interface read from K^1, K^2
     * (ReducedMatrix). Shared with the AMG hierarchy built from it: ML
     * applies the matrix it was built from in its V-cycles, so a reused
     * hierarchy keeps that matrix alive after the next Newton step
     * replaced it. */
    std::shared_ptr<ReducedMatrix> reduced;
    TrilinosWrappers::MPI::Vector  reduced_rhs;
    /** Owned indices of the components eliminated in this step. */
    std::vector<types::global_dof_index> eliminated_dofs;

    /** (active, stick, slip sign) of each owned slave node in this step,
     * and when the AMG hierarchy was built. */
    std::vector<std::array<int, 3>> node_states;
    /** (weighted gap, weighted slip) of each owned slave node. */
    std::vector<std::array<double, 2>> node_data;
    std::vector<std::array<int, 3>>    states_at_build;
    /** A stale hierarchy costs GMRES iterations roughly in proportion to
     * the nodes that changed, a new one its setup: reuse pays for a few
     * changed nodes only (measurements in doc/contact.md section 2). */
    static constexpr unsigned int max_changed_nodes_for_reuse = 4;

    std::shared_ptr<const ReducedMatrix> amg_matrix;
    std::unique_ptr<ElasticityAMG>       amg;
    /** Krylov iterations of the first solve with the current hierarchy,
     * and of the last solve. */
    unsigned int fresh_iterations = 0;
    unsigned int last_iterations  = 0;
    /** u of the last solve (empty before the first one on this mesh). */
    TrilinosWrappers::MPI::Vector last_solution;
    /** No slip node with friction and no coupling to a constrained master
     * DoF anywhere: Z~ = Z, CG applies. */
    bool symmetric = true;
  };
} // namespace coulomb_adapt

#endif
