#ifndef coulomb_adapt_contact_contact_linear_solver_choice_h
#define coulomb_adapt_contact_contact_linear_solver_choice_h

#include <deal.II/base/types.h>

#include <coulomb_adapt/core/parameters.h>

#include <string>

namespace coulomb_adapt
{
  /**
   * Which linear solver takes the contact Newton systems, and why: the
   * sparse direct solver on the row-replacing system, or Krylov + AMG on
   * the system with the contact conditions eliminated. 'Linear
   * solver/Type = auto' chooses by the DoFs of both bodies against
   * 'Maximum DoFs for direct contact' (the crossover measured in
   * benchmarks/contact/README.md, "Direct against Krylov + AMG: the
   * crossover"); direct and amg are taken as given.
   */
  struct ContactLinearSolverChoice
  {
    /** Krylov + AMG on the eliminated system. */
    bool iterative = false;
    /** For the log: the solver and the reason, e.g. "direct
     * (Amesos_Mumps): 7764 DoFs <= 'Linear solver/Maximum DoFs for direct
     * contact' (20000)". */
    std::string description;
  };

  /**
   * Under 'Linear solver/Type = auto', a Krylov solve of a contact Newton
   * system that does not converge within
   * max_krylov_iterations_under_auto hands that system to the direct
   * solver (ContactSolver::newton_step), and this record keeps the
   * failure: every later Newton system that shares the record goes to the
   * direct solver at once. The ContactSolveDriver shares one record
   * between all its solves (load steps, restarts, later cycles), so an
   * ill-conditioned problem (contact_stagnation: a stiff, nearly
   * incompressible body 1 on a soft, locking body 2) pays for one failed
   * Krylov solve per run, not one per Newton step. Its conditioning does
   * not improve on refined meshes, so a later cycle would fail again.
   */
  struct KrylovFailureRecord
  {
    /** Empty until a Krylov solve failed; then where and how, for the
     * log, e.g. "Newton step 1, 5220 DoFs: gmres+amg stopped at 200
     * iterations, residual 6.7e-07". */
    std::string failure;
    /** Krylov solves that failed and were repeated by the direct solver:
     * at most 1 per record, since the record then chooses direct. */
    unsigned int n_failed_solves = 0;

    bool
    failed() const
    {
      return !failure.empty();
    }
  };

  /**
   * The iteration limit of a Krylov solve of a contact Newton system under
   * 'Linear solver/Type = auto' ('Maximum iterations' if lower), at which
   * the system goes to the direct solver instead. The solves that converge
   * take 7-48 iterations (GMRES or CG with AMG, 10^3-10^6 DoFs, 1 and 2
   * ranks, to 1e-12 |b|: the benchmarks' logs); a system that needs more
   * is ill-conditioned for AMG (contact_stagnation's reached 6.7e-7 |b| in
   * 1000), and 200 iterations of it cost little next to the direct solve.
   */
  constexpr unsigned int max_krylov_iterations_under_auto = 200;

  /** The choice for @p n_dofs (both bodies); under 'auto', a @p record of
   * a failed Krylov solve makes it the direct solver. */
  ContactLinearSolverChoice
  choose_contact_linear_solver(const parameters::LinearSolver &parameters,
                               const types::global_dof_index   n_dofs,
                               const KrylovFailureRecord      &record = {});
} // namespace coulomb_adapt

#endif
