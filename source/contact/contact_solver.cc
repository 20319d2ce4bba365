#include <deal.II/base/timer.h>

#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/contact/body_equilibrium.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_linear_solver_choice.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/eliminated_contact_system.h>
#include <coulomb_adapt/contact/first_step_rule.h>
#include <coulomb_adapt/contact/newton_diagnostics.h>
#include <coulomb_adapt/contact/row_replacing_contact_system.h>
#include <coulomb_adapt/contact/set_change_control.h>
#include <coulomb_adapt/contact/tighter_krylov_solve.h>

#include <algorithm>
#include <array>
#include <iomanip>
#include <limits>
#include <sstream>

namespace coulomb_adapt
{
  namespace
  {
    // Where nothing faces body 2 because the curves touch at more than 60
    // degrees from facing (the mortar leaves such pairs out,
    // MortarInterface::reinit): say so, instead of "the curves do not face
    // each other". Empty where no such pair touches.
    std::string
    steep_contact_advice(const MortarInterface &mortar)
    {
      const auto &steep = mortar.steep_contact();
      if (!steep)
        return "";
      std::ostringstream m;
      m << std::setprecision(3) << "at (" << steep->position[0] << ", "
        << steep->position[1] << ") the curves touch at " << steep->angle
        << " degrees from facing each other (a sharp wedge or corner), "
        << "and the mortar pairs only segments whose normals are within 60 "
        << "degrees of opposite (steeper pairs are left out: the gap along "
        << "the slave normal is not reliable there; doc/contact.md). Make "
        << "the contact curves "
        << "meet less steeply there: a blunter wedge (flanks at most 60 "
        << "degrees from body 2's surface), or a rounded tip.";
      return m.str();
    }
  } // namespace



  ContactSolver::ContactSolver(
    ElasticBody                         &slave,
    ElasticBody                         &master,
    const parameters::Contact           &contact_parameters,
    const parameters::LinearSolver      &solver_parameters,
    const ConditionalOStream            &pcout,
    std::shared_ptr<KrylovFailureRecord> krylov_failures)
    : slave(slave)
    , master(master)
    , contact_parameters(contact_parameters)
    , solver_parameters(solver_parameters)
    , pcout(pcout)
    , mu(contact_parameters.friction_coefficient)
    , krylov_failures(krylov_failures ? std::move(krylov_failures) :
                                        std::make_shared<KrylovFailureRecord>())
  {}



  // The semismooth Newton method as a primal-dual active set iteration:
  // solve the linear problem of the current sets, evaluate the multipliers,
  // gaps and slips of its solution, and let the complementarity functions
  // choose the next sets, until the rule no longer changes them and the
  // complementarity residual is below the tolerance. SetChangeControl
  // guards the iteration against cycles and stagnation; the diagnoses
  // name what went wrong when it fails.
  void
  ContactSolver::iterate(ContactSolverReport &report)
  {
    report.frictionless = (mu == 0);
    SetChangeControl control(rule,
                             states,
                             previous_weighted_slip,
                             support,
                             restriction_allowed(),
                             pcout);
    linear_tolerance_factor                   = 1;
    residual_before_tighter_solve             = 0;
    unsigned int              n_turning_steps = 0;
    std::vector<unsigned int> last_changed;
    // The first load step without sets from another mesh (those are kept
    // until the load step ends) starts from the initial gap.
    const bool from_initial_gap =
      load_step_start.empty() && warm_start_states.empty();
    for (unsigned int k = 1; k <= contact_parameters.max_newton_iterations; ++k)
      {
        control.begin_step(k);
        const bool turning = check_sets(k);
        n_turning_steps += turning;
        // A Krylov solve whose sets come out unchanged but whose residual
        // does not is solved again, more tightly, within the same step:
        // the sets, hence the linear system, are those of step k (the
        // slip directions are part of the sets), so the repeat refines
        // step k's solve and is not a new linearisation.
        NextStep next = NextStep::repeat_linear_solve;
        while (next == NextStep::repeat_linear_solve)
          {
            const auto [assembly_time, solve_time] =
              newton_step(k, turning, report.n_active);

            // The statuses before the update, for the first step's rule only.
            std::vector<ContactStatus> before;
            if (k == 1 && from_initial_gap)
              for (const auto &s : states)
                before.push_back(s.status);
            auto         update   = control.update_sets(k);
            unsigned int n_opened = 0;
            if (!before.empty())
              n_opened =
                close_deepest_penetration_only(before, support, states, update);
            const double residual =
              complementarity_residual(rule, previous_weighted_slip, states);
            last_changed = update.changed;
            record_step(k, residual, report);
            newton_diagnostics::log_newton_step(pcout,
                                                k,
                                                report,
                                                mu,
                                                update,
                                                residual,
                                                assembly_time,
                                                solve_time,
                                                iterative ? &last_linear_solve :
                                                            nullptr);
            if (n_opened > 0)
              pcout << "    first step from the initial gap: " << n_opened
                    << " newly penetrating nodes left open (less than "
                    << first_step_penetration_fraction
                    << " times the deepest penetration)" << std::endl;
            next = next_step(k, update, residual, turning, control, report);
          }
        if (next == NextStep::converged)
          break;
      }

    if (!report.converged)
      throw newton_diagnostics::iteration_limit(
        contact_parameters.max_newton_iterations,
        report.residual_history,
        states,
        last_changed,
        n_turning_steps);
  }



  // Body 1 must be held by the sets of step k (or the diagnosis stops the
  // solve). A free rotation makes the system singular too, but with a
  // balanced load it still has solutions (a disc on its first contact
  // node), and the next step's sets decide; otherwise the solve goes
  // astray, which the diagnoses then name.
  bool
  ContactSolver::check_sets(const unsigned int k) const
  {
    // Neither body held by its Dirichlet data: the pair moves as one rigid
    // body whatever the sets, and no Newton step can fix that.
    if (!support.holds_all_rigid_motions() &&
        !holds_all_rigid_motions(master_gram))
      throw ContactDiagnosis(
        "Newton step " + std::to_string(k) +
          ": neither body is held by "
          "Dirichlet data: body 1 (" +
          slave.name() + ") and body 2 (" + master.name() +
          ") can move together as one rigid body, whatever the contact "
          "sets. Hold one of them (a 'Fixed components' group, or the "
          "scene's supports).",
        k - 1);
    newton_diagnostics::check_support(
      support, states, mu, k, slave.name(), steep_contact_advice(mortar));
    check_master_support(k);
    const bool turning = support.rotation_free(states);
    if (turning)
      pcout << "    body 1 can turn about its active node(s) in these "
               "sets: the system is singular"
            << std::endl;
    return turning;
  }



  // Body 2 is held by its Dirichlet data, or, floating, by the contact
  // alone: then, as for body 1, the sets must have an active node,
  // without friction its Dirichlet data must hold its slide along the
  // interface (a frictionless contact does not), and with friction the
  // sets must not leave it a rigid slide with every node slipping. Otherwise
  // the system is singular and body 2's rigid motion arbitrary (and different
  // on 1 and 2 ranks).
  void
  ContactSolver::check_master_support(const unsigned int k) const
  {
    if (holds_all_rigid_motions(master_gram))
      return;
    unsigned int n_active = 0;
    for (const auto &s : states)
      n_active += (s.status != ContactStatus::open);
    const std::string where =
      "Newton step " + std::to_string(k) + ": body 2 (" + master.name() + ") ";
    if (n_active == 0)
      throw ContactDiagnosis(where + "has no active contact node and its "
                                     "Dirichlet data do not hold it: "
                                     "nothing holds it (is it loaded "
                                     "towards body 1?).",
                             k - 1);
    const Tensor<1, 2> tangent = interface_tangent();
    if (mu == 0 && tangent.norm() > 0 &&
        !holds_translation_along(master_gram, tangent))
      throw ContactDiagnosis(where + "can slide freely along the "
                                     "frictionless interface: its Dirichlet "
                                     "data do not hold it tangentially. Hold "
                                     "it, or use friction.",
                             k - 1);
    // With friction, as for body 1: all active nodes slipping must not
    // leave body 2 a rigid motion along the interface (a shaft turning in
    // its hub under a torque beyond mu times the pressure's moment).
    if (mu > 0)
      newton_diagnostics::check_sliding(rigid_motion_left_free(master_gram,
                                                               Point<2>(),
                                                               states),
                                        states,
                                        mu,
                                        k,
                                        "body 2 (" + master.name() + ")");
  }



  void
  ContactSolver::record_step(const unsigned int   k,
                             const double         residual,
                             ContactSolverReport &report) const
  {
    // A repeated linear solve (NextStep::repeat_linear_solve) replaces its
    // step's residual: one entry per Newton step.
    if (report.residual_history.size() == k)
      report.residual_history.back() = residual;
    else
      report.residual_history.push_back(residual);
    report.newton_iterations = k;
    report.n_active = report.n_stick = report.n_slip = 0;
    for (const auto &s : states)
      if (s.status != ContactStatus::open)
        {
          ++report.n_active;
          (s.status == ContactStatus::stick ? report.n_stick : report.n_slip)++;
        }
  }



  // Converged: the full rule changes no set and the residual is below the
  // tolerance, or below the round-off of the multipliers, which are
  // differences of nodal forces (with a stiff, nearly incompressible body
  // 1 that floor lies above the tolerance). Unchanged sets above both stop
  // the solve, unless the linear solve was a Krylov solve: the same
  // system is then solved again from this solution with a tighter
  // tolerance (few iterations, and the AMG hierarchy is reused), up to
  // twice (contact/tighter_krylov_solve.h). Changed sets go to
  // SetChangeControl.
  ContactSolver::NextStep
  ContactSolver::next_step(const unsigned int                 k,
                           const SetChangeControl::SetUpdate &update,
                           const double                       residual,
                           const bool                         turning,
                           SetChangeControl                  &control,
                           ContactSolverReport               &report)
  {
    const double floor              = residual_round_off_floor();
    report.residual_round_off_floor = floor;
    if (update.n_changed == 0 &&
        residual <= std::max(contact_parameters.tolerance, floor))
      {
        check_equilibrium(k);
        accepted_residual_of_solve =
          std::max(contact_parameters.tolerance, floor);
        report.converged           = true;
        report.slave_rotation_free = turning;
        newton_diagnostics::log_convergence(
          pcout, turning, residual, contact_parameters.tolerance, floor);
        return NextStep::converged;
      }
    if (update.n_changed == 0 && iterative &&
        repeat_krylov_solve_tighter(report.n_tighter_linear_solves,
                                    residual,
                                    residual_before_tighter_solve))
      {
        ++report.n_tighter_linear_solves;
        residual_before_tighter_solve = residual;
        linear_tolerance_factor *= tighter_krylov_factor;
        pcout << "    sets unchanged, residual above the tolerance: "
              << "step " << k << "'s linear solve is repeated with its "
              << "tolerance reduced to " << linear_tolerance_factor << " times"
              << std::endl;
        return NextStep::repeat_linear_solve;
      }
    if (update.n_changed == 0)
      throw newton_diagnostics::residual_above_tolerance(
        k, residual, contact_parameters.tolerance, floor);
    if (const auto repeated = control.repeated_step())
      {
        if (control.damp(k, *repeated))
          return NextStep::iterate;
        throw newton_diagnostics::cycling(k,
                                          *repeated,
                                          report.residual_history,
                                          states,
                                          update.changed,
                                          control.n_damping_steps(),
                                          iterative);
      }
    control.record(update, residual);
    return NextStep::iterate;
  }



  // Converged sets are not yet an answer: a singular system (a body that
  // the sets do not hold) can meet the contact conditions node by node
  // with forces that do not balance the load. Each body's free rigid
  // motions must balance to round-off (contact/body_equilibrium.h).
  void
  ContactSolver::check_equilibrium(const unsigned int k) const
  {
    const double linear_tolerance =
      iterative ? std::min(solver_parameters.relative_tolerance, 1e-12) *
                    linear_tolerance_factor :
                  0.;
    const std::array<const ElasticBody *, 2> bodies = {{&slave, &master}};
    for (unsigned int b = 0; b < 2; ++b)
      {
        const BodyEquilibrium e = body_equilibrium(
          *bodies[b], b == 0, mortar, states, linear_tolerance);
        if (!e.balanced())
          throw ContactDiagnosis(
            "Newton step " + std::to_string(k) +
              ": the contact sets "
              "converged, but " +
              equilibrium_message("body " + std::to_string(b + 1) + " (" +
                                    bodies[b]->name() + ")",
                                  e),
            k);
      }
  }



  void
  ContactSolver::setup()
  {
    mortar.reinit(slave, master);
    AssertThrow(mortar.slave_nodes().size() > 0,
                ExcMessage("The contact boundary of body 1 is empty."));
    condensation.reinit(mortar, slave, master);

    // c = scale E_c / D_jj with the combined modulus E_c = E1 E2 / (E1 +
    // E2), which follows the softer body: with the stiffer one's modulus a
    // soft partner makes c and the residual scale meaningless.
    const auto &D             = mortar.slave_weights();
    rule.friction_coefficient = mu;
    rule.tolerance            = contact_parameters.tolerance;
    rule.combined_modulus     = combined_modulus();
    rule.complementarity_constant.resize(D.size());
    for (unsigned int j = 0; j < D.size(); ++j)
      rule.complementarity_constant[j] =
        contact_parameters.complementarity_scale * rule.combined_modulus / D[j];

    // IndexSet::size(): the DoFs of both bodies, the same on every rank.
    const bool use_iterative =
      choose_contact_linear_solver(solver_parameters,
                                   condensation.owned.size(),
                                   *krylov_failures)
        .iterative;
    if (!newton_system || use_iterative != iterative)
      {
        if (use_iterative)
          newton_system = std::make_unique<EliminatedContactSystem>();
        else
          newton_system = std::make_unique<RowReplacingContactSystem>();
      }
    iterative = use_iterative;
    newton_system->reinit(mortar, slave, master, condensation);

    setup_states();
  }



  // With body 1 held along the interface (a prescribed tangential
  // displacement) the sets may cycle, and damping c resolves that, while
  // restricted changes would drift to all-slip sets; without friction
  // there is no stick set to restrict.
  bool
  ContactSolver::restriction_allowed() const
  {
    if (mu == 0)
      return false;
    const Tensor<1, 2> tangent = interface_tangent();
    return tangent.norm() > 0 && !support.holds_translation_along(tangent);
  }



  std::pair<double, double>
  ContactSolver::newton_step(const unsigned int k,
                             const bool         rotation_free,
                             const unsigned int n_active)
  {
    Timer      assembly_timer;
    const auto conditions = slave_node_conditions(
      condensation, mortar, states, previous_weighted_slip, mu);
    newton_system->assemble(conditions);
    assembly_timer.stop();
    Timer solve_timer;
    try
      {
        try
          {
            solve_newton_system();
          }
        catch (const SolverControl::NoConvergence &e)
          {
            if (!iterative ||
                solver_parameters.type != LinearSolverType::automatic)
              throw;
            // The same system, solved directly: the Newton iteration goes
            // on as if the direct solver had taken it from the start.
            switch_to_direct_solver(k, e);
            newton_system->assemble(conditions);
            solve_newton_system();
          }
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw newton_diagnostics::krylov_failure(k, e);
      }
    catch (const std::exception &e)
      {
        throw newton_diagnostics::linear_solve_failure(k,
                                                       n_active,
                                                       rotation_free,
                                                       e);
      }
    solve_timer.stop();
    evaluate_contact_state();
    return {assembly_timer.wall_time(), solve_timer.wall_time()};
  }



  // The Krylov solve failed on a system that the direct solver takes
  // (the same sets): from here on, and in every solve that shares the
  // record, the direct solver takes the Newton systems, so that an
  // ill-conditioned problem pays for one failed Krylov solve, not one per
  // Newton step.
  void
  ContactSolver::switch_to_direct_solver(const unsigned int                  k,
                                         const SolverControl::NoConvergence &e)
  {
    std::ostringstream failure;
    failure << "Newton step " << k << ", " << condensation.owned.size()
            << " DoFs: stopped at " << e.last_step << " iterations, residual "
            << e.last_residual;
    krylov_failures->failure = failure.str();
    ++krylov_failures->n_failed_solves;
    pcout << "    the Krylov solve did not converge in " << e.last_step
          << " iterations (residual " << e.last_residual
          << "): this system and the following ones go to the direct "
             "solver"
          << std::endl;
    iterative       = false;
    near_null_space = std::vector<std::vector<double>>();
    newton_system   = std::make_unique<RowReplacingContactSystem>();
    newton_system->reinit(mortar, slave, master, condensation);
  }



  // The multipliers are differences of large nodal forces (f - K u at the
  // slave rows): a Krylov solve to the usual relative tolerance leaves the
  // complementarity residual above the default Contact/Tolerance, so the
  // solve is at least to 1e-12.
  void
  ContactSolver::solve_newton_system()
  {
    const MPI_Comm                communicator = condensation.communicator;
    TrilinosWrappers::MPI::Vector solution(condensation.owned, communicator);
    parameters::LinearSolver      settings = solver_parameters;
    settings.type =
      iterative ? LinearSolverType::amg : LinearSolverType::direct;
    settings.relative_tolerance =
      std::min(settings.relative_tolerance, 1e-12) * linear_tolerance_factor;
    // Under 'auto' a system that AMG does not solve quickly goes to the
    // direct solver (newton_step()), and the failed attempt is cheap.
    if (solver_parameters.type == LinearSolverType::automatic)
      settings.max_iterations =
        std::min(settings.max_iterations, max_krylov_iterations_under_auto);
    last_linear_solve =
      newton_system->solve(near_null_space, settings, solution);

    TrilinosWrappers::MPI::Vector u1(slave.locally_owned_dof_set(),
                                     communicator);
    TrilinosWrappers::MPI::Vector u2(master.locally_owned_dof_set(),
                                     communicator);
    for (const auto i : slave.locally_owned_dof_set())
      u1(i) = solution(i);
    for (const auto i : master.locally_owned_dof_set())
      u2(i) = solution(condensation.offset + i);
    u1.compress(VectorOperation::insert);
    u2.compress(VectorOperation::insert);
    slave.set_solution(u1);
    master.set_solution(u2);
  }



  // The multipliers lambda_j, the nodal gaps and slips of the interface,
  // in normal and tangential components; everything on every rank.
  void
  ContactSolver::evaluate_contact_state()
  {
    const auto &nodes      = mortar.slave_nodes();
    const auto multipliers = condensation.multipliers(mortar, slave.solution());
    multiplier_round_off   = multipliers.round_off;
    const auto &lambda     = multipliers.lambda;
    const auto  gaps = mortar.nodal_gaps(slave.solution(), master.solution());
    for (unsigned int j = 0; j < nodes.size(); ++j)
      {
        states[j].pressure            = lambda[j] * nodes[j].normal;
        states[j].tangential_traction = lambda[j] * nodes[j].tangent;
        states[j].facing_master       = mortar.is_covered(j);
        states[j].gap                 = gaps[j].gap;
        states[j].slip                = gaps[j].slip;
      }
  }



  // The complementarity residual's counterpart of multiplier_round_off:
  // normalised by the largest pressure, as the residual is.
  double
  ContactSolver::residual_round_off_floor() const
  {
    // The tangential function is mu p (lambda_t - trial): its round-off
    // grows with mu (mu = 1e10 stuck all-stick at a residual of 1e-6).
    return multiplier_round_off / largest_pressure(states) * std::max(1., mu);
  }



  Tensor<1, 2>
  ContactSolver::interface_tangent() const
  {
    Tensor<1, 2> tangent;
    for (unsigned int j = 0; j < states.size(); ++j)
      if (mortar.is_covered(j))
        tangent += states[j].tangent;
    return tangent.norm() > 0 ? tangent / tangent.norm() : tangent;
  }



  double
  ContactSolver::combined_modulus() const
  {
    const double E1 = slave.description().material.youngs_modulus;
    const double E2 = master.description().material.youngs_modulus;
    return E1 * E2 / (E1 + E2);
  }



  // Near null space of the combined system for AMG: the three joint rigid
  // modes of the two bodies (both rotate about the origin), and without
  // friction also body 1 sliding along the interface (its translation
  // along the mean tangent), which the frictionless contact does not
  // resist. Joint modes rather than each body's own keep the coarse
  // problems of the aggregates small; the comparison is in doc/contact.md
  // section 2.
  std::vector<std::vector<double>>
  ContactSolver::rigid_body_modes() const
  {
    const auto                      &modes_1 = slave.rigid_body_modes();
    const auto                      &modes_2 = master.rigid_body_modes();
    std::vector<std::vector<double>> modes;
    for (unsigned int m = 0; m < 3; ++m)
      {
        modes.push_back(modes_1[m]);
        modes.back().insert(modes.back().end(),
                            modes_2[m].begin(),
                            modes_2[m].end());
      }
    const Tensor<1, 2> tangent = interface_tangent();
    if (mu == 0 && tangent.norm() > 0)
      {
        std::vector<double> slide(modes.front().size(), 0.);
        for (std::size_t k = 0; k < modes_1[0].size(); ++k)
          slide[k] = tangent[0] * modes_1[0][k] + tangent[1] * modes_1[1][k];
        modes.push_back(std::move(slide));
      }
    return modes;
  }



  const LinearSolverReport &
  ContactSolver::last_linear_solver_report() const
  {
    return last_linear_solve;
  }



  void
  ContactSolver::release_newton_system()
  {
    newton_system.reset();
    near_null_space = std::vector<std::vector<double>>();
  }



  const std::vector<ContactNodeState> &
  ContactSolver::node_states() const
  {
    return states;
  }



  const MortarInterface &
  ContactSolver::mortar_interface() const
  {
    return mortar;
  }



  double
  ContactSolver::accepted_residual() const
  {
    return accepted_residual_of_solve;
  }
} // namespace coulomb_adapt
