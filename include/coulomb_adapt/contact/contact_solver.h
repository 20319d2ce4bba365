#ifndef coulomb_adapt_contact_contact_solver_h
#define coulomb_adapt_contact_contact_solver_h

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/rigid_motion_gram.h>
#include <coulomb_adapt/contact/active_set.h>
#include <coulomb_adapt/contact/condensed_newton_system.h>
#include <coulomb_adapt/contact/contact_linear_solver_choice.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/contact/set_change_control.h>
#include <coulomb_adapt/contact/slave_support.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <memory>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /** What a contact solve did, for the log and summary.json. */
  struct ContactSolverReport
  {
    unsigned int newton_iterations = 0;
    bool         converged         = false;
    unsigned int n_active = 0, n_stick = 0, n_slip = 0;
    /** Force of body 2 on body 1, sum of D_jj R_j (N/mm). */
    Tensor<1, 2> contact_force;
    /** Moment of the same tractions about the origin, counterclockwise,
     * sum of x_j x D_jj R_j at the slave nodes' positions (N mm/mm): the
     * torque a joint transmits by contact. */
    double              contact_moment       = 0;
    double              max_contact_pressure = 0;
    std::vector<double> residual_history;
    /** Round-off floor of the multipliers at the last Newton step
     * (residual_round_off_floor()); convergence accepts a residual up to
     * max(Contact/Tolerance, this). */
    double residual_round_off_floor = 0;
    /** Nodes whose sets the load step predictor changed from the previous
     * load step's (predict_next_load_step; 0 without prediction). */
    unsigned int n_predicted_changes = 0;
    /** Newton steps of a predicted start that stopped with a diagnosis,
     * before the step was solved again from the previous step's sets. */
    unsigned int newton_iterations_of_stopped_prediction = 0;
    /** Krylov solves repeated with a tighter tolerance because unchanged
     * sets missed Contact/Tolerance (0, 1 or 2: ContactSolver::next_step). */
    unsigned int n_tighter_linear_solves = 0;
    bool         frictionless            = false;
    /** The converged sets and body 1's Dirichlet data leave its rigid
     * rotation free: its displacement is fixed only up to it. */
    bool slave_rotation_free = false;
  };

  /**
   * Static two-body Coulomb contact, theory.md section 2: the mortar
   * interface with Wohlmuth's dual multiplier basis, and the semismooth
   * Newton method of Hüeber, Stadler and Wohlmuth in its primal-dual active
   * set form. In 2D, with the sets (open / stick / slip, and the slip
   * direction) fixed, the conditions are linear, and the dual basis makes
   * the multipliers explicit, lambda_j = (f^1 - K^1 u^1)_j / D_jj: each
   * Newton step solves for the displacements of both bodies only.
   *
   * solve() is the Newton driver; the parts live in their own files:
   * - MortarInterface: D, M and the weighted gaps;
   * - SlaveCondensation and CondensedNewtonSystem: the condensed system of
   *   one step, row-replacing for direct solvers or with the conditions
   *   eliminated for Krylov + AMG (RowReplacingContactSystem,
   *   EliminatedContactSystem);
   * - active_set.h: the rule that reads the next sets off the
   *   complementarity functions (c_n = c_t = scale E_c / D_jj,
   *   E_c = E1 E2 / (E1 + E2)), and the residual;
   * - SetChangeControl: damping, restriction, cycle and stagnation
   *   detection;
   * - SlaveSupport: whether the sets hold body 1;
   * - newton_diagnostics.h: the log lines and the diagnoses.
   *
   * mu = 0 takes the frictionless path: active nodes carry no tangential
   * traction, there are no stick or slip sets.
   */
  class ContactSolver : public ContactSolution
  {
  public:
    /** @p krylov_failures: the record of failed Krylov solves that this
     * solver shares with others of the same run (ContactSolveDriver), or
     * none (a record of its own). */
    ContactSolver(ElasticBody                         &slave,
                  ElasticBody                         &master,
                  const parameters::Contact           &contact_parameters,
                  const parameters::LinearSolver      &solver_parameters,
                  const ConditionalOStream            &pcout,
                  std::shared_ptr<KrylovFailureRecord> krylov_failures = {});

    /** Solve one load step; the bodies' solutions are set. Throws with a
     * diagnosis when the iteration does not converge. The bodies' systems
     * must be assembled (with the loads of this step). Called again for
     * the next load step on the same meshes, it starts from the sets of
     * the previous step, and stick means no slip *in this step*: the
     * quasi-static, incremental form of Coulomb's law. A single call is the
     * static problem of the seed. */
    ContactSolverReport
    solve();

    /** Start the next solve from the sets of @p previous (the node states
     * of a solve on another mesh of the same bodies): each slave node takes
     * the status and slip direction of the nearest previous node. Without
     * it (or if that leaves a floating body 1 without active node) the
     * sets start from the initial gap. */
    void
    warm_start_from(const std::vector<ContactNodeState> &previous);

    /**
     * Start the next load step (the next solve() on the same meshes) from
     * sets predicted for its loads, the continuation predictor of a
     * proportional load path: each slave node's multipliers, gap and slip
     * go on by @p increment_ratio times their increments in the last load
     * step, and the active set rule reads the sets off that state. With
     * the sets fixed a Newton step's solution depends on the sets alone,
     * so the prediction is one of the sets; the converged solution does
     * not depend on it (the iteration runs to its own convergence). If
     * the predicted start stops with a diagnosis, the step is solved again
     * from the sets of the step before. Without a last increment (the
     * first two load steps on these meshes) it does nothing.
     */
    void
    predict_next_load_step(const double increment_ratio);

    /** The last linear solve of the Newton iteration. */
    const LinearSolverReport &
    last_linear_solver_report() const;

    /** Free the Newton system (the eliminated system's copy of K, the
     * reduced matrices and the AMG hierarchy, or the direct solver's
     * factorisation) once no further load step will be solved: the node
     * states, the mortar interface and the bodies' solutions stay. The
     * indicator and the output then run in that memory instead of on top
     * of it (benchmarks/adaptive_run/README.md, "Memory"). A later solve()
     * builds the system again. */
    void
    release_newton_system();

    const std::vector<ContactNodeState> &
    node_states() const override;

    const MortarInterface &
    mortar_interface() const override;

    double
    accepted_residual() const override;

  private:
    /** The mortar integrals, the condensation, the Newton system for the
     * chosen solver, the constants of the active set rule and the states
     * of this load step. */
    void
    setup();
    /** Positions, normals and weights of the slave nodes in the states;
     * on a new mesh also the initial (or warm-started) sets. */
    void
    setup_states();
    void
    initialize_sets();
    /** The sets of predict_next_load_step() in the states; returns the
     * number of nodes whose sets it changed. */
    unsigned int
    predict_sets();
    /** The Newton iteration of one load step from the current sets. */
    void
    iterate(ContactSolverReport &report);
    void
    transfer_warm_start_sets();
    /** Whether set changes may be restricted when the iteration stalls:
     * only for a body 1 that friction alone holds tangentially. */
    bool
    restriction_allowed() const;
    /** The support test of Newton step @p k (throws if body 1 is not
     * held); returns whether its rotation is free. */
    bool
    check_sets(const unsigned int k) const;
    /** The same for body 2, whose Dirichlet data may leave it floating
     * (throws the diagnosis if the sets of step @p k do not hold it). */
    void
    check_master_support(const unsigned int k) const;
    /** Assemble and solve the Newton system of step @p k for the current
     * sets, and evaluate the contact state of its solution. Returns the
     * wall times of assembly and solve. */
    std::pair<double, double>
    newton_step(const unsigned int k,
                const bool         rotation_free,
                const unsigned int n_active);
    void
    solve_newton_system();
    /** Under 'Linear solver/Type = auto', the Krylov solve of Newton step
     * @p k did not converge (@p e): the failure is recorded, logged, and
     * the direct solver's system replaces the eliminated one. */
    void
    switch_to_direct_solver(const unsigned int                  k,
                            const SolverControl::NoConvergence &e);
    /** The residual and the sets of step @p k in the report. */
    void
    record_step(const unsigned int   k,
                const double         residual,
                ContactSolverReport &report) const;
    enum class NextStep
    {
      converged,
      iterate,
      /** The sets are final but an inexact (Krylov) solve left the
       * residual above the tolerance: the same step's system again, more
       * tightly. */
      repeat_linear_solve
    };
    /** Convergence test, repeated Krylov solve, cycles and stagnation
     * after the set update of step @p k; throws the diagnosis when the
     * iteration cannot go on. */
    NextStep
    next_step(const unsigned int                 k,
              const SetChangeControl::SetUpdate &update,
              const double                       residual,
              const bool                         turning,
              SetChangeControl                  &control,
              ContactSolverReport               &report);
    /** The force balance of both bodies for the converged sets of step
     * @p k; throws the diagnosis if one does not balance. */
    void
    check_equilibrium(const unsigned int k) const;
    void
    evaluate_contact_state();
    /** After convergence: the slip of this load step, the slip history
     * for the next one, and the contact force. */
    void
    finish_load_step(ContactSolverReport &report);
    std::vector<std::vector<double>>
    rigid_body_modes() const;
    /** E1 E2 / (E1 + E2): the modulus that scales c and the residual. */
    double
    combined_modulus() const;
    /** The complementarity residual that round-off alone can leave:
     * multiplier_round_off / (largest pressure). */
    double
    residual_round_off_floor() const;
    /** The unit mean tangent of the slave nodes that face the master
     * side (zero if none does): the direction in which body 1 slides. */
    Tensor<1, 2>
    interface_tangent() const;

    ElasticBody                   &slave;
    ElasticBody                   &master;
    const parameters::Contact      contact_parameters;
    const parameters::LinearSolver solver_parameters;
    const ConditionalOStream      &pcout;
    const double                   mu;

    MortarInterface   mortar;
    SlaveCondensation condensation;
    ActiveSetRule     rule;
    SlaveSupport      support;
    /** Body 2's Gram matrix of its supported rigid motions (rotation
     * about the origin), once per load step. */
    FullMatrix<double> master_gram;
    /** Bound on the round-off of the nodal multipliers at the last
     * evaluation (MPa). */
    double multiplier_round_off = 0;
    /** max(Contact/Tolerance, round-off floor) of the converged step. */
    double accepted_residual_of_solve = 0;

    /** Krylov + AMG: the Newton systems are solved with the contact
     * conditions eliminated; direct solves take the row-replacing
     * system. Decided in setup() from 'Linear solver/Type' and
     * @p krylov_failures, and switched to direct by a failed Krylov
     * solve under 'auto' (switch_to_direct_solver()). The system
     * persists from one load step to the next (the eliminated one starts
     * its Krylov solves from the last solution). */
    bool                                   iterative = false;
    std::unique_ptr<CondensedNewtonSystem> newton_system;
    std::shared_ptr<KrylovFailureRecord>   krylov_failures;
    LinearSolverReport                     last_linear_solve;
    /** rigid_body_modes() of this load step, for the AMG path; empty for
     * direct solves. */
    std::vector<std::vector<double>> near_null_space;
    /** Factor on the Krylov tolerance: 1, then 1e-2 and 1e-4 when
     * unchanged sets miss the complementarity tolerance (next_step). */
    double linear_tolerance_factor = 1;
    /** The residual of the step's solve before its last tighter repeat. */
    double residual_before_tighter_solve = 0;

    std::vector<ContactNodeState> states;
    /** States of a previous mesh to start from (warm_start_from). */
    std::vector<ContactNodeState> warm_start_states;
    /** Weighted tangential jump at the end of the previous load step. */
    std::vector<double> previous_weighted_slip;
    /** The converged states of the previous load step on these meshes
     * (empty in the first): the start of this step's increments, and of
     * its solve again if a predicted start stops. */
    std::vector<ContactNodeState> load_step_start;
    /** Each node's change of pressure, tangential traction, gap and slip
     * in the last load step (empty until a load step had a start). */
    struct Increment
    {
      double pressure, tangential_traction, gap, slip;
    };
    std::vector<Increment> last_increments;
    /** predict_next_load_step()'s ratio for the next solve (0: none). */
    double predictor_ratio = 0;
  };
} // namespace coulomb_adapt

#endif
