#ifndef coulomb_adapt_contact_newton_diagnostics_h
#define coulomb_adapt_contact_newton_diagnostics_h

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/set_change_control.h>
#include <coulomb_adapt/contact/slave_support.h>

#include <exception>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * What the contact solver tells: one log line per Newton step, and the
   * diagnoses (ContactDiagnosis) with which it stops, each naming what
   * went wrong and what to try (doc/contact.md section 6).
   */
  namespace newton_diagnostics
  {
    /** Is body 1 held by the sets of Newton step @p step? Without active
     * nodes nothing holds it at all, unless its own Dirichlet data do;
     * with every active node slipping, a rigid motion along which every
     * normal gap stays put is free (check_sliding): the system would be
     * singular, and the static problem has no solution. Throws the
     * diagnosis if not. @p why_nothing_faces, if not empty, replaces the
     * advice when no node faces body 2 (where the curves touch too
     * steeply to be paired). */
    void
    check_support(const SlaveSupport                  &support,
                  const std::vector<ContactNodeState> &states,
                  const double                         friction_coefficient,
                  const unsigned int                   step,
                  const std::string                   &body_name,
                  const std::string                   &why_nothing_faces);

    /** Does a body whose contact nodes all slip slide? @p
     * rigid_motion_free: whether the sets and the body's Dirichlet data
     * leave a rigid motion free (rigid_motion_left_free). With every
     * active node slipping and such a motion, the system is singular and
     * the sets have no equilibrium: throws the diagnosis, naming @p
     * body_label ("body 2 (hub)"). Which body floats does not matter. */
    void
    check_sliding(const bool                           rigid_motion_free,
                  const std::vector<ContactNodeState> &states,
                  const double                         friction_coefficient,
                  const unsigned int                   step,
                  const std::string                   &body_label);

    /** The Krylov solver of Newton step @p step did not converge. */
    ContactDiagnosis
    krylov_failure(const unsigned int                  step,
                   const SolverControl::NoConvergence &e);

    /** The linear solve of Newton step @p step failed otherwise. */
    ContactDiagnosis
    linear_solve_failure(const unsigned int    step,
                         const unsigned int    n_active,
                         const bool            rotation_free,
                         const std::exception &e);

    /** The sets no longer change, but the residual stays above the
     * tolerance and the round-off @p floor. */
    ContactDiagnosis
    residual_above_tolerance(const unsigned int step,
                             const double       residual,
                             const double       tolerance,
                             const double       floor);

    /** The sets after step @p step repeat those of step @p repeated, and
     * damping could not break the cycle. */
    ContactDiagnosis
    cycling(const unsigned int                   step,
            const unsigned int                   repeated,
            const std::vector<double>           &residual_history,
            const std::vector<ContactNodeState> &states,
            const std::vector<unsigned int>     &changed,
            const unsigned int                   n_damping_steps,
            const bool                           iterative_solver_chosen);

    /** The iteration limit @p max_steps was reached. */
    ContactDiagnosis
    iteration_limit(const unsigned int                   max_steps,
                    const std::vector<double>           &residual_history,
                    const std::vector<ContactNodeState> &states,
                    const std::vector<unsigned int>     &changed,
                    const unsigned int                   n_turning_steps);

    /** The log line of Newton step @p step. @p linear_solve is given for
     * iterative solves (its iterations are shown). */
    void
    log_newton_step(const ConditionalOStream          &pcout,
                    const unsigned int                 step,
                    const ContactSolverReport         &report,
                    const double                       friction_coefficient,
                    const SetChangeControl::SetUpdate &update,
                    const double                       residual,
                    const double                       assembly_time,
                    const double                       solve_time,
                    const LinearSolverReport          *linear_solve);

    /** The notes on converged sets: body 1's rotation left free, or a
     * residual accepted within the round-off @p floor. */
    void
    log_convergence(const ConditionalOStream &pcout,
                    const bool                rotation_free,
                    const double              residual,
                    const double              tolerance,
                    const double              floor);
  } // namespace newton_diagnostics
} // namespace coulomb_adapt

#endif
