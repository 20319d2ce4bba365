#include <deal.II/base/utilities.h>

#include <coulomb_adapt/core/units.h>
#include <coulomb_adapt/output/cycle_report.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace coulomb_adapt
{
  namespace
  {
    nlohmann::json
    element_effectivity_record(const ExactErrorComparison &c)
    {
      return {{"mean", c.element_effectivity_mean},
              {"std", c.element_effectivity_std},
              {"min", c.element_effectivity_min},
              {"max", c.element_effectivity_max},
              {"n_elements", c.n_elements}};
    }
  } // namespace



  CycleReport::CycleReport(const MPI_Comm            mpi_communicator,
                           const ConditionalOStream &pcout,
                           const TimerOutput        &timer,
                           const std::string        &summary_file,
                           const std::string        &scene,
                           const std::string        &parameter_file)
    : mpi_communicator(mpi_communicator)
    , pcout(pcout)
    , timer(timer)
    , summary(mpi_communicator, summary_file, scene, parameter_file)
  {}



  void
  CycleReport::set_run_entry(const std::string    &key,
                             const nlohmann::json &value)
  {
    summary.set(key, value);
  }



  void
  CycleReport::set_load_scale(const double load_scale)
  {
    units::Scales s;
    s.stress       = load_scale;
    s.displacement = load_scale;
    set_scales(s);
  }



  void
  CycleReport::set_scales(const units::Scales &scales)
  {
    this->scales = scales;
    summary.set("load_scale", scales.stress);
    if (scales.displacement != scales.stress)
      summary.set("displacement_scale", scales.displacement);
  }



  // With P = D = 1 (ordinary problems) every number is reported as it is.
  double
  CycleReport::physical(const double       scaled,
                        const units::Kind  kind,
                        const std::string &key)
  {
    double value = scaled;
    if ((scales.stress == 1 && scales.displacement == 1) ||
        units::to_physical(scaled, scales, kind, value))
      return value;
    // With D = P (loads scaled alone) as load_scale's power.
    const char *factor[2][4] = {
      {"load_scale^1", "load_scale^1", "load_scale^2", "load_scale^1"},
      {"load_scale",
       "displacement_scale",
       "load_scale times displacement_scale",
       "the square root of load_scale times displacement_scale"}};
    const bool         two_scales = scales.stress != scales.displacement;
    std::ostringstream reason;
    reason << std::setprecision(6) << "times "
           << factor[two_scales][static_cast<int>(kind)]
           << " (load_scale = " << scales.stress;
    if (two_scales)
      reason << ", displacement_scale = " << scales.displacement;
    reason << ") " << key << " = " << scaled
           << " of the scaled problem is no finite double";
    report_scaled(key, reason.str());
    return scaled;
  }



  void
  CycleReport::report_scaled(const std::string &key, const std::string &reason)
  {
    if (!scaled_keys.insert(key).second)
      return;
    pcout << "  units: " << key << " reported in the scaled form: " << reason
          << std::endl;
    summary.set("reported_scaled",
                std::vector<std::string>(scaled_keys.begin(),
                                         scaled_keys.end()));
  }



  void
  CycleReport::begin_cycle(const unsigned int cycle)
  {
    this->cycle = cycle;
    cycle_timer.restart();
    times_before    = timer.get_summary_data(TimerOutput::total_wall_time);
    record          = {{"cycle", cycle}};
    body_records    = nlohmann::json::array();
    n_dofs_of_cycle = 0;
  }



  types::global_dof_index
  CycleReport::n_dofs() const
  {
    return n_dofs_of_cycle;
  }



  std::optional<double>
  CycleReport::exact_error() const
  {
    for (const char *key : {"epsilon_exact_extrapolated", "epsilon_exact"})
      if (record.contains(key))
        return record[key].get<double>();
    return std::nullopt;
  }



  void
  CycleReport::record_claimed_bound(const double estimate)
  {
    const std::optional<double> exact = exact_error();
    if (!exact)
      return;
    const bool holds      = estimate >= *exact;
    record["bound_holds"] = holds;
    if (!holds)
      pcout << "  warning: the estimate is below the exact error it claims "
               "to bound: epsilon = "
            << std::fixed << std::setprecision(3) << 100 * estimate
            << " % < exact " << 100 * *exact
            << " %; check the reference's own error (summary.json "
               "exact_error_reference_error; 'Error indicator/Reference "
               "refinements') and the local problems' degree ('Error "
               "indicator/CRE degree increase', doc/indicator.md 4b)"
            << std::defaultfloat << std::endl;
  }



  void
  CycleReport::record_contact_solve(const ContactSolveOutcome &outcome)
  {
    const ContactSolverReport &report = outcome.report;
    record["warm_start"]              = outcome.warm_start;
    if (outcome.nested_iteration)
      {
        nlohmann::json nested = {{"levels", nlohmann::json::array()}};
        if (!outcome.nested_iteration->skipped.empty())
          nested["skipped"] = outcome.nested_iteration->skipped;
        for (const NestedIterationLevel &l : outcome.nested_iteration->levels)
          {
            nlohmann::json level = {{"global_refinements",
                                     l.global_refinements},
                                    {"graded_zone_coarsening", l.coarsening},
                                    {"n_dofs", l.n_dofs},
                                    {"newton_iterations", l.newton_iterations},
                                    {"active_nodes", l.n_active},
                                    {"wall_time_s", l.wall_time}};
            if (l.from_own_hierarchy)
              level["finest_cell_level"] = l.finest_cell_level;
            if (l.every_size_scaled)
              level["every_mesh_size_scaled"] = true;
            if (!l.newton_iterations_per_load_step.empty())
              level["newton_iterations_per_load_step"] =
                l.newton_iterations_per_load_step;
            nested["levels"].push_back(level);
          }
        record["nested_iteration"] = nested;
      }
    for (const std::string &key : outcome.restarts)
      record[key] = true;
    record["load_steps"] = outcome.n_load_steps;
    record["newton_iterations_per_load_step"] =
      outcome.newton_iterations_per_load_step;

    pcout << "  contact: initial gap: largest overlap "
          << outcome.initial_overlap << " mm, largest clearance "
          << outcome.initial_clearance << " mm" << std::endl;
    record["initial_overlap"]   = outcome.initial_overlap;
    record["initial_clearance"] = outcome.initial_clearance;
    record["linear_solver"]     = {
          {{"method", outcome.linear_solver.method},
           {"iterations", outcome.linear_solver.n_iterations}}};
    if (!outcome.krylov_failure.empty())
      record["linear_solver"][0]["krylov_failure"] = outcome.krylov_failure;
    const double force[2] = {
      physical(report.contact_force[0], units::Kind::stress, "contact_force"),
      physical(report.contact_force[1], units::Kind::stress, "contact_force")};
    const double max_pressure = physical(report.max_contact_pressure,
                                         units::Kind::stress,
                                         "max_contact_pressure");
    pcout << "  contact: " << report.newton_iterations << " Newton steps, "
          << report.n_active << " active nodes, "
          << "contact force (" << force[0] << ", " << force[1]
          << ") N/mm, max pressure " << max_pressure << " MPa" << std::endl;
    record["newton_iterations"] = report.newton_iterations;
    if (outcome.newton_iterations_of_stopped_starts > 0)
      record["newton_iterations_of_stopped_starts"] =
        outcome.newton_iterations_of_stopped_starts;
    record["converged"]            = report.converged;
    record["active_nodes"]         = report.n_active;
    record["stick_nodes"]          = report.n_stick;
    record["slip_nodes"]           = report.n_slip;
    record["contact_force"]        = {force[0], force[1]};
    record["max_contact_pressure"] = max_pressure;
    record["frictionless"]         = report.frictionless;
    record["contact_moment"] =
      physical(report.contact_moment, units::Kind::stress, "contact_moment");
    if (outcome.n_load_steps > 1)
      {
        std::vector<double> moments;
        for (const double m : outcome.contact_moment_per_load_step)
          moments.push_back(
            physical(m, units::Kind::stress, "contact_moment_per_load_step"));
        pcout << "  contact: moment of the contact tractions on body 1 "
                 "about the origin per load step (N mm/mm):";
        for (const double m : moments)
          pcout << " " << m;
        pcout << std::endl;
        record["contact_moment_per_load_step"] = moments;
      }
    if (report.slave_rotation_free)
      record["body_1_rotation_free"] = true;
    record["residual_history"]         = report.residual_history;
    record["residual_round_off_floor"] = report.residual_round_off_floor;
  }



  void
  CycleReport::record_linear_solve(const ElasticBody        &body,
                                   const LinearSolverReport &report,
                                   const double              wall_time)
  {
    pcout << "  " << body.name() << ": solved by " << report.method;
    if (report.method == "cg+amg")
      pcout << " (" << report.n_iterations << " iterations)";
    pcout << " in " << std::setprecision(3) << wall_time << " s" << std::endl;
    if (!record["linear_solver"].is_array())
      record["linear_solver"] = nlohmann::json::array();
    record["linear_solver"].push_back(
      {{"method", report.method}, {"iterations", report.n_iterations}});
  }



  // The correction of the contact fields (theory.md section 3): the
  // nodal reactions projected onto the Coulomb cone, or skipped.
  void
  CycleReport::record_correction(const CorrectedContactSolution &c)
  {
    if (c.skipped && !c.within_solve_accuracy)
      pcout << "  correction: skipped, the FE reactions are in the "
               "Coulomb cone (corrected fields = FE fields)";
    else
      pcout << "  correction: " << c.n_projected_nodes
            << " nodal reactions projected onto the Coulomb cone, "
               "relative change "
            << std::scientific << std::setprecision(3) << c.relative_change
            << ", largest nodal change " << std::setprecision(2)
            << c.largest_nodal_change << std::defaultfloat
            << (c.within_solve_accuracy ?
                  ": within the contact solve's accepted residual, the "
                  "corrected problem is skipped (U_c = U_h)" :
                  "; corrected problem solved");
    const double max_penetration = physical(c.max_penetration,
                                            units::Kind::displacement,
                                            "max_penetration_clipped");
    if (c.max_penetration > 0)
      pcout << "; penetration up to " << std::setprecision(3) << max_penetration
            << " mm clipped";
    pcout << std::endl;
    record["correction"] = {{"skipped", c.skipped},
                            {"within_solve_accuracy", c.within_solve_accuracy},
                            {"largest_nodal_change", c.largest_nodal_change},
                            {"relative_change", c.relative_change},
                            {"projected_nodes", c.n_projected_nodes},
                            {"max_penetration_clipped", max_penetration}};
  }



  // How the cre estimator's R_c on quadratic segments was put in the
  // Coulomb cone between the nodes (doc/indicator.md 4c): a line when
  // coefficients were raised, a warning when the force and moment were
  // not restored or the Lagrange coefficients had to be kept.
  nlohmann::json
  CycleReport::log_bernstein_traction(
    const BernsteinContactTraction::Report &b) const
  {
    if (b.lagrange_fallback)
      pcout << "  cre: warning: sigma^'s contact traction in Bernstein form: "
            << b.n_raised << " of " << b.n_segments
            << " quadratic segments needed their middle coefficient raised "
               "into the Coulomb cone, and no rescaling factor >= 0 "
               "restores the FE's contact force and moment: the Lagrange "
               "interpolant's coefficients are used, which leave the cone "
               "between the nodes"
            << std::endl;
    else if (!b.resultant_restored())
      pcout << "  cre: warning: sigma^'s contact traction in Bernstein form: "
            << b.n_raised << " of " << b.n_segments
            << " middle coefficients raised into the Coulomb cone; contact "
               "force and moment restored only to "
            << std::scientific << std::setprecision(2) << b.resultant_defect
            << std::defaultfloat << " (relative) after " << b.n_rounds
            << " rounds, so sigma^ balances the bodies' loads only to that "
               "accuracy (see the equilibration's defect)"
            << std::endl;
    else if (b.n_raised > 0)
      pcout << "  cre: sigma^'s contact traction in Bernstein form: "
            << b.n_raised << " of " << b.n_segments
            << " quadratic segments' middle coefficients raised into the "
               "Coulomb cone, contact force and moment restored in "
            << b.n_rounds << " rounds (to " << std::scientific
            << std::setprecision(1) << b.resultant_defect << std::defaultfloat
            << ")" << std::endl;
    return {{"segments", b.n_segments},
            {"raised", b.n_raised},
            {"rounds", b.n_rounds},
            {"resultant_defect", b.resultant_defect},
            {"resultant_restored", b.resultant_restored()},
            {"lagrange_fallback", b.lagrange_fallback}};
  }



  // The cre estimator's equilibration in the log: the degree, the
  // defects, and what the optimisation of the edge tractions gained.
  void
  CycleReport::log_equilibration(const ErrorEstimate &e,
                                 const unsigned int   cre_degree_increase) const
  {
    pcout << "  cre: equilibrated stress (local problems of degree p + "
          << cre_degree_increase << ")"
          << (e.has_contact ? " from the solution under the consistent "
                              "contact load (solved: the mortar's "
                              "dual-basis traction is not in the cone "
                              "between the nodes)" :
                              "")
          << "; node systems' defect " << std::scientific
          << std::setprecision(1) << e.node_system_defect
          << ", local problems' rigid-motion load " << e.local_problem_defect
          << std::defaultfloat << std::endl;
    if (e.misses_held_reaction())
      pcout << "  cre: warning: the reaction of nodes held by the scene's "
               "point constraints but on no held line of faces (a mesh "
               "file's point supports) is not carried by the equilibrated "
               "stress: up to "
            << std::scientific << std::setprecision(1)
            << e.uncarried_held_reaction << std::defaultfloat
            << " of the largest element residual, so sigma^ is not exactly "
               "statically admissible and epsilon is not a guaranteed bound "
               "(doc/indicator.md)"
            << std::endl;
    if (e.optimisation_parameters > 0)
      pcout << "  cre: edge tractions optimised (" << e.optimisation_parameters
            << " parameters; prolongation conditions "
            << (e.relaxed_equilibration[0] && e.relaxed_equilibration[1] ?
                  "relaxed" :
                e.relaxed_equilibration[0] || e.relaxed_equilibration[1] ?
                  "relaxed in one body" :
                !e.relaxed_equilibration_requested ?
                  "kept: 'CRE relaxed equilibration = false'" :
                  "kept: the relaxed modes need 'CRE degree increase' >= 3 "
                  "and displacement data that the FE space interpolates "
                  "exactly or 'CRE lift of displacement data = true'")
            << (e.optimisation_steps > 0 ?
                  "; " + std::to_string(e.optimisation_steps) +
                    " truncated CG steps" +
                    (e.exact_minimisation_too_large ?
                       std::string(", as a body's system has more "
                                   "parameters than 'CRE exact "
                                   "minimisation up to'") :
                       std::string()) :
                  std::string())
            << "); with the classical tractions epsilon would be " << std::fixed
            << std::setprecision(3) << 100 * e.epsilon_before_optimisation
            << " %"
            << (e.opened_nodes[0] + e.opened_nodes[1] > 0 || e.narrow_opening ?
                  " (without the opening of the kinematic side below)" :
                  "")
            << std::defaultfloat << std::endl;
    if (e.evaluation_degree_increase > 0)
      {
        pcout << "  cre: evaluated with local problems of degree p + "
              << cre_degree_increase + e.evaluation_degree_increase;
        if (e.optimisation_parameters > 0)
          pcout << ", not those of the minimisation (p + "
                << cre_degree_increase
                << "), whose minimum is where they see least of sigma^";
        for (unsigned int b = 0; b < 2; ++b)
          if (e.classical_tractions_kept[b])
            pcout << "; body " << b + 1
                  << " keeps the classical tractions (the optimised ones "
                     "evaluated there are above them)";
        pcout << std::endl;
      }
  }



  // Where U_c penetrates between the mortar's nodes, the cre bound needs
  // the kinematic side opened (kinematic_admissibility.h): the log says by
  // how much, and what it costs the estimate.
  nlohmann::json
  CycleReport::log_kinematic_admissibility(const ErrorEstimate &e)
  {
    const double penetration =
      physical(e.penetration, units::Kind::displacement, "penetration");
    const double after = physical(e.penetration_after,
                                  units::Kind::displacement,
                                  "penetration_after_opening");
    if (e.penetration == 0)
      pcout << "  cre: the kinematic side does not penetrate between the "
               "mortar's nodes (checked pointwise)"
            << std::endl;
    else
      {
        pcout << "  cre: the kinematic side penetrates by up to "
              << std::setprecision(3) << penetration
              << " mm between the mortar's nodes (at x = "
              << e.penetration_at[0] << ", y = " << e.penetration_at[1] << ")";
        if (!e.opening_applied)
          pcout << "; with friction the estimate is no bound, so it is not "
                   "opened";
        else
          {
            // The narrow opening (narrow_opening.h), then the nodes the
            // nodal one moved for the rest.
            const auto &narrow = e.narrow_opening;
            const bool  nodal  = e.opened_nodes[0] + e.opened_nodes[1] > 0;
            pcout << ": opened ";
            if (narrow)
              pcout << (narrow->side == 0 ? "the slave" : "the master")
                    << " body on " << narrow->cells << " cells bisected "
                    << narrow->refinements << " times (" << narrow->fine_cells
                    << " fine cells, narrower than the judged ones)"
                    << (nodal ? " and " : "");
            if (nodal || !narrow)
              pcout << e.opened_nodes[0] << " slave and " << e.opened_nodes[1]
                    << " master nodes";
            pcout << " to remove it, ||sigma(u^ - U_c)|| / D "
                  << (narrow ? "<= " : "= ") << std::fixed
                  << std::setprecision(3) << 100 * e.epsilon_opening
                  << " %, which the bound adds twice (doc/indicator.md 4c)"
                  << std::defaultfloat;
          }
        if (e.penetration_after > 0)
          pcout << "; " << std::setprecision(3) << after
                << " mm remain, which no free node could open: the estimate "
                   "is no bound";
        pcout << std::endl;
      }
    if (e.negative_pressure > 1e-8)
      pcout << "  cre: the equilibrated pressure is negative between the "
               "nodes (down to "
            << std::setprecision(3) << e.negative_pressure
            << " of the largest, Lagrange interpolation: its Bernstein form "
               "would not balance the bodies): sigma^ is not "
               "admissible there, the estimate is no bound"
            << std::endl;
    nlohmann::json record = {{"penetration", penetration},
                             {"negative_pressure_relative",
                              e.negative_pressure}};
    if (e.opening_applied)
      {
        record["opened_nodes"] = {e.opened_nodes[0], e.opened_nodes[1]};
        record["penetration_after_opening"] = after;
        record["epsilon_opening"]           = e.epsilon_opening;
        record["opening_work_relative"]     = e.opening_work_relative;
        if (const auto &narrow = e.narrow_opening)
          record["narrow_opening"] = {{"body",
                                       narrow->side == 0 ? "slave" : "master"},
                                      {"cells", narrow->cells},
                                      {"refinements", narrow->refinements},
                                      {"fine_cells", narrow->fine_cells}};
      }
    return record;
  }



  void
  CycleReport::record_error_estimate(
    const ErrorEstimate                      &e,
    const std::vector<const ErrorEstimate *> &compared,
    const unsigned int                        cre_degree_increase)
  {
    if (e.has_contact)
      record_correction(e.correction);
    nlohmann::json admissibility;
    nlohmann::json bernstein_traction;
    if (e.estimator == ErrorEstimator::cre)
      {
        log_equilibration(e, cre_degree_increase);
        if (e.bernstein_traction)
          bernstein_traction = log_bernstein_traction(*e.bernstein_traction);
        if (e.has_contact)
          admissibility = log_kinematic_admissibility(e);
        if (e.epsilon_dirichlet_lift > 0)
          pcout << "  cre: the displacement data are not interpolated "
                   "exactly; their interpolation error's lift r has "
                   "||sigma(r)|| / D = "
                << std::fixed << std::setprecision(3)
                << 100 * e.epsilon_dirichlet_lift
                << " %, which the bound adds to ||sigma^ - sigma(u_c + r)|| "
                   "(doc/indicator.md 4b)"
                << std::defaultfloat << std::endl;
      }
    auto log_epsilon = [&](const ErrorEstimate &estimate) {
      pcout << "  error indicator (" << to_string(estimate.estimator)
            << "): epsilon = " << std::fixed << std::setprecision(3)
            << 100 * estimate.epsilon << " % (volume: body 1 "
            << 100 * estimate.epsilon_volume[0] << " %, body 2 "
            << 100 * estimate.epsilon_volume[1] << " %; contact "
            << 100 * estimate.epsilon_contact << " %)" << std::defaultfloat
            << (&estimate == &e ? "" : " [compared, not driving]") << std::endl;
    };
    log_epsilon(e);
    for (const ErrorEstimate *other : compared)
      log_epsilon(*other);

    record["epsilon"]         = e.epsilon;
    record["epsilon_volume"]  = {e.epsilon_volume[0], e.epsilon_volume[1]};
    record["epsilon_contact"] = e.epsilon_contact;
    record["estimator"]       = to_string(e.estimator);
    if (e.estimator != ErrorEstimator::cre)
      record["recovery"] = to_string(e.recovery);
    else
      record["cre"] = {
        {"degree_increase", cre_degree_increase},
        {"node_system_defect", e.node_system_defect},
        {"local_problem_defect", e.local_problem_defect},
        {"uncarried_held_reaction", e.uncarried_held_reaction},
        {"optimisation_parameters", e.optimisation_parameters},
        {"optimisation_cg_steps", e.optimisation_steps},
        {"exact_minimisation_too_large", e.exact_minimisation_too_large},
        {"relaxed_equilibration",
         {e.relaxed_equilibration[0], e.relaxed_equilibration[1]}},
        {"epsilon_classical_tractions", e.epsilon_before_optimisation},
        {"evaluation_degree_increase", e.evaluation_degree_increase},
        {"classical_tractions_kept",
         {e.classical_tractions_kept[0], e.classical_tractions_kept[1]}},
        {"kinematic_admissibility", admissibility}};
    if (e.bernstein_traction)
      record["cre"]["bernstein_traction"] = bernstein_traction;
    if (e.estimator == ErrorEstimator::cre)
      record["cre"]["epsilon_dirichlet_lift"] = e.epsilon_dirichlet_lift;
    if (compared.empty())
      return;
    // cre's part from the lift of the displacement data (0 where none is
    // needed): a reader comparing the three needs it to split cre's
    // epsilon as the driving record does.
    auto record_of = [this](const ErrorEstimate &estimate) {
      nlohmann::json r{{"epsilon", estimate.epsilon},
                       {"epsilon_volume",
                        {estimate.epsilon_volume[0],
                         estimate.epsilon_volume[1]}},
                       {"epsilon_contact", estimate.epsilon_contact},
                       {"normalisation_squared",
                        physical(estimate.normalisation_squared,
                                 units::Kind::energy,
                                 "normalisation_squared")},
                       {"wall_time_s", estimate.wall_time}};
      if (estimate.estimator == ErrorEstimator::cre)
        r["epsilon_dirichlet_lift"] = estimate.epsilon_dirichlet_lift;
      return r;
    };
    nlohmann::json estimators;
    estimators[to_string(e.estimator)] = record_of(e);
    for (const ErrorEstimate *other : compared)
      estimators[to_string(other->estimator)] = record_of(*other);
    record["estimators"] = estimators;
  }



  void
  CycleReport::announce_reference_solution(const unsigned int r)
  {
    pcout << "  exact error: solving the reference problem (this cycle's "
             "meshes refined "
          << r << " times) and, for its own error, "
          << (r > 1 ? "the same refined " + std::to_string(r - 1) + " times" :
                      std::string("comparing it with this cycle's solution"))
          << std::endl;
  }



  void
  CycleReport::record_exact_error(
    const std::string &reference,
    const std::vector<std::pair<ErrorEstimator, ExactErrorComparison>>
      &comparisons)
  {
    const ExactErrorComparison &c = comparisons.front().second;
    pcout << "  exact error (" << reference
          << "): epsilon_exact = " << std::fixed << std::setprecision(3)
          << 100 * c.epsilon_exact << " %, effectivity " << c.effectivity
          << " (elements: mean " << c.element_effectivity_mean << ", std "
          << c.element_effectivity_std << ", min " << c.element_effectivity_min
          << ", max " << c.element_effectivity_max << ")" << std::defaultfloat
          << std::endl;
    record["epsilon_exact"]         = c.epsilon_exact;
    record["effectivity"]           = c.effectivity;
    record["element_effectivity"]   = element_effectivity_record(c);
    record["exact_error_reference"] = reference;
    if (comparisons.size() == 1)
      return;
    for (const auto &[estimator, x] : comparisons)
      {
        record["estimators"][to_string(estimator)].update(
          {{"epsilon_exact", x.epsilon_exact},
           {"effectivity", x.effectivity},
           {"element_effectivity", element_effectivity_record(x)}});
        pcout << "  exact error of " << to_string(estimator)
              << "'s corrected solution: " << std::fixed << std::setprecision(3)
              << 100 * x.epsilon_exact << " %, effectivity " << x.effectivity
              << std::defaultfloat << std::endl;
      }
  }



  void
  CycleReport::record_reference_solution(
    const ReferenceSolutionStress &reference,
    const double                   energy,
    const double                   reference_energy,
    const double                   epsilon_energy)
  {
    const double strain_energy =
      physical(energy, units::Kind::energy, "strain_energy");
    const double reference_strain_energy[2] = {
      physical(reference.strain_energy(0),
               units::Kind::energy,
               "reference_strain_energy"),
      physical(reference.strain_energy(1),
               units::Kind::energy,
               "reference_strain_energy")};
    pcout << "  exact error: reference's own error " << std::fixed
          << std::setprecision(3) << 100 * reference.own_error()
          << " % (from the energies " << 100 * reference.own_error_from_energy()
          << " %); energy check: epsilon_energy = " << 100 * epsilon_energy
          << " % ("
          << (reference_energy >= energy ?
                "U_ref >= U_h, as for loads: e^2 = 2 (U_ref - U_h)" :
                "U_h > U_ref, as for prescribed displacements or overlap: "
                "e^2 = 2 (U_h - U_ref)")
          << "; strain energy " << std::scientific << strain_energy
          << ", reference "
          << physical(reference_energy,
                      units::Kind::energy,
                      "reference_strain_energy")
          << ")" << std::defaultfloat << std::endl;
    record["exact_error_reference_error"] = reference.own_error();
    record["exact_error_reference_error_energy"] =
      reference.own_error_from_energy();
    record["exact_error_reference_dofs"] = reference.n_dofs();
    record["reference_strain_energy"]    = {reference_strain_energy[0],
                                            reference_strain_energy[1]};
    record["epsilon_energy"]             = epsilon_energy;
    record["energy_check_driven_by"] =
      reference_energy >= energy ? "loads" : "displacements";

    // The computed exact error is low by the reference's own error
    // (theory.md section 8): extrapolated from the three levels (judged,
    // R - 1, R; extrapolated_exact_error), else (levels not yet
    // asymptotic) about sqrt(epsilon_exact^2 + e_ref^2). The effectivity
    // against it is the one to judge an estimator by where the reference
    // is not much finer than the judged mesh (singular corners).
    // With R = 1 the level below the reference is the judged mesh itself:
    // its "own error" is epsilon_exact again, and the fallback would add
    // epsilon_exact to itself (sqrt(2) epsilon_exact, 40 % above the truth
    // on the quarter press fit, P2). No extrapolation then.
    if (reference.n_refinements() < 2)
      {
        pcout << "  exact error: not extrapolated: with 'Error indicator/"
                 "Reference refinements' = 1 the reference's own error is "
                 "measured against this cycle's solution, i.e. it is "
                 "epsilon_exact itself (an upper bound of the reference's "
                 "error, not an estimate); 2 or more extrapolate"
              << std::endl;
        return;
      }
    const auto add_extrapolation = [&](nlohmann::json    &r,
                                       const std::string &name) {
      if (!r.contains("epsilon_exact") || !r.contains("epsilon"))
        return;
      const double against_reference = r["epsilon_exact"];
      const double extrapolated =
        extrapolated_exact_error(against_reference,
                                 reference.own_error(),
                                 reference.n_refinements());
      const double truth =
        extrapolated > 0 ? extrapolated :
                           std::hypot(against_reference, reference.own_error());
      const double effectivity =
        truth > 0 ? r["epsilon"].get<double>() / truth : 0.;
      r["epsilon_exact_extrapolated"] = truth;
      r["effectivity_extrapolated"]   = effectivity;
      r["exact_error_extrapolation"]  = extrapolated > 0 ?
                                          "geometric over the levels" :
                                          "reference error added";
      pcout << "  exact error" << name << " extrapolated ("
            << (extrapolated > 0 ?
                  "judged, R - 1 and R levels" :
                  "not asymptotic: sqrt(epsilon_exact^2 + e_ref^2)")
            << "): " << std::fixed << std::setprecision(3) << 100 * truth
            << " %, effectivity " << effectivity << std::defaultfloat
            << std::endl;
    };
    add_extrapolation(record, "");
    if (record.contains("estimators") && record["estimators"].size() > 1)
      for (auto &[name, estimator] : record["estimators"].items())
        add_extrapolation(estimator, " of " + name);
  }



  void
  CycleReport::record_body_error(const unsigned int      b,
                                 const ElasticBody      &body,
                                 const ElasticityErrors &e)
  {
    const double l2 =
      physical(e.l2, units::Kind::displacement, "exact_error.l2");
    const double energy =
      physical(e.energy, units::Kind::energy_norm, "exact_error.energy");
    pcout << "  " << body.name() << ": error against the exact solution: L2 "
          << std::scientific << std::setprecision(3) << l2 << " mm, energy "
          << energy << " (relative " << e.energy / e.energy_of_exact << ")"
          << std::defaultfloat << std::endl;
    body_records[b]["exact_error"] = {{"l2", l2},
                                      {"energy", energy},
                                      {"relative_energy",
                                       e.energy / e.energy_of_exact}};
  }



  void
  CycleReport::record_strain_energy(const unsigned int b, const double energy)
  {
    body_records[b]["strain_energy"] =
      physical(energy, units::Kind::energy, "strain_energy");
  }



  void
  CycleReport::end_cycle(const ErrorEstimate &estimate, const bool has_contact)
  {
    cycle_timer.stop();
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    record["bodies"]      = body_records;
    record["n_dofs"]      = n_dofs_of_cycle;
    record["wall_time_s"] = cycle_timer.wall_time();
    // Per-phase wall times of this cycle (rank 0's clock).
    nlohmann::json timings;
    for (const auto &[section, total] :
         timer.get_summary_data(TimerOutput::total_wall_time))
      {
        const auto before = times_before.find(section);
        timings[section] =
          total - (before == times_before.end() ? 0. : before->second);
      }
    record["timings_s"] = timings;
    // Peak resident memory so far: largest rank, and all ranks together.
    record["peak_memory_MiB"] =
      Utilities::MPI::max(memory.VmHWM / 1024., mpi_communicator);
    record["peak_memory_total_MiB"] =
      Utilities::MPI::sum(memory.VmHWM / 1024., mpi_communicator);
    summary.add_cycle(record);

    // The per-cycle line a user watches, and the final table's row.
    const unsigned int newton = record.value("newton_iterations", 0u);
    pcout << "Cycle " << cycle << ": " << n_dofs_of_cycle
          << " DoFs, epsilon = " << std::fixed << std::setprecision(3)
          << 100 * estimate.epsilon
          << " %, epsilon_contact = " << 100 * estimate.epsilon_contact << " %"
          << std::defaultfloat;
    if (has_contact)
      pcout << ", " << newton << " Newton steps";
    pcout << ", " << std::setprecision(3) << cycle_timer.wall_time() << " s"
          << std::endl;
    table.add_value("cycle", cycle);
    table.add_value("cells 1", body_records[0]["n_cells"].get<unsigned int>());
    table.add_value("cells 2", body_records[1]["n_cells"].get<unsigned int>());
    table.add_value("DoFs", n_dofs_of_cycle);
    table.add_value("eps %", 100 * estimate.epsilon);
    table.add_value("eps_c %", 100 * estimate.epsilon_contact);
    if (has_contact)
      table.add_value("Newton", newton);
    table.add_value("time s", cycle_timer.wall_time());
  }



  void
  CycleReport::record_stop(const unsigned int cycle, const std::string &reason)
  {
    pcout << "Adaptation stops after cycle " << cycle << ": " << reason
          << std::endl;
    summary.set("status", "completed");
    summary.set("stop_reason", reason);
  }



  std::string
  CycleReport::record_failure(const unsigned int cycle,
                              const std::string &message)
  {
    return summary.record_failure(cycle, message);
  }



  void
  CycleReport::print_table()
  {
    for (const std::string column : {"eps %", "eps_c %", "time s"})
      table.set_precision(column, 3);
    for (const std::string column : {"eps %", "eps_c %"})
      table.set_scientific(column, false);
    if (pcout.is_active())
      {
        pcout.get_stream() << std::endl;
        table.write_text(pcout.get_stream(), TableHandler::org_mode_table);
      }
  }
} // namespace coulomb_adapt
