#include <deal.II/base/utilities.h>

#include <coulomb_adapt/adaptation/optimal_size.h>
#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/bodies/elasticity_errors.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/core/finiteness.h>
#include <coulomb_adapt/contact/nested_iteration.h>
#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <iomanip>
#include <sstream>

namespace coulomb_adapt
{
  TwoBodyProblem::TwoBodyProblem(const MPI_Comm     mpi_communicator,
                                 const Parameters & parameters,
                                 ParameterHandler & prm,
                                 const std::string &parameter_file,
                                 std::ostream &     log)
    : mpi_communicator(mpi_communicator)
    , parameters(parameters)
    , pcout(log,
            Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    // No communicator: the timer's destructor must not synchronise the
    // ranks while an exception unwinds (that could deadlock).
    , computing_timer(pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times)
    , target_calibration(parameters.adaptation.target_safety_factor)
  {
    scene   = scenes::create_scene(parameters, prm);
    if (parameters.scene.name == "gmsh")
      {
        prm.enter_subsection("Scene");
        prm.enter_subsection("Gmsh");
        mesh_source = "gmsh file '" + prm.get("Mesh file") + "': ";
        prm.leave_subsection();
        prm.leave_subsection();
      }
    summary = std::make_unique<RunSummary>(
      mpi_communicator,
      parameters.output.directory + "/summary.json",
      scene->name(),
      parameter_file);
    if (!scene->reference_values().empty())
      summary->set("reference", scene->reference_values());
    summary->set("friction_coefficient",
                 parameters.contact.friction_coefficient);
    check_initial_mesh_size();
  }



  const ElasticBody &
  TwoBodyProblem::body(const unsigned int b) const
  {
    return *bodies[b];
  }



  const ErrorEstimate &
  TwoBodyProblem::last_error_estimate() const
  {
    Assert(error_estimate, ExcMessage("no cycle has run"));
    return *error_estimate;
  }



  void
  TwoBodyProblem::setup_system()
  {
    TimerOutput::Scope t(computing_timer, "setup");
    for (auto &body : bodies)
      body->setup_system();
  }



  void
  TwoBodyProblem::assemble_system()
  {
    TimerOutput::Scope t(computing_timer, "assembly");
    for (auto &body : bodies)
      body->assemble_system();
  }



  // Each body is solved on its own; a body without Dirichlet support would
  // need contact to be held, so it is stopped here with a diagnosis rather
  // than handed to a solver that would return garbage for a singular
  // matrix.
  void
  TwoBodyProblem::solve()
  {
    if (has_contact())
      solve_contact();
    else
      solve_separately();
    check_finite_solution(bodies, contact_solver.get());
  }



  bool
  TwoBodyProblem::has_contact() const
  {
    return bodies[0]->description().contact_boundary_id !=
             numbers::invalid_boundary_id &&
           bodies[1]->description().contact_boundary_id !=
             numbers::invalid_boundary_id;
  }



  // Both bodies coupled through the mortar contact interface.
  void
  TwoBodyProblem::solve_contact()
  {
    TimerOutput::Scope t(computing_timer, "contact solve");
    pcout << "  contact: " << (parameters.contact.friction_coefficient > 0 ?
                                 "Coulomb friction, mu = " +
                                   Patterns::Tools::Convert<double>::to_string(
                                     parameters.contact.friction_coefficient) :
                                 std::string("frictionless (mu = 0): no "
                                             "stick/slip sets"))
          << std::endl;
    // A solver with contact parameters @p c, from the initial gap or
    // from predicted sets.
    const auto new_contact_solver =
      [&](const parameters::Contact &               c,
          const std::vector<ContactNodeState> *predicted_sets) {
        contact_solver = std::make_unique<ContactSolver>(
          *bodies[0], *bodies[1], c, parameters.linear_solver, pcout);
        if (predicted_sets != nullptr)
          contact_solver->warm_start_from(*predicted_sets);
      };
    const bool static_problem = scene->n_load_steps() == 1;
    const bool warm_start = parameters.adaptation.warm_start &&
                            !previous_contact_states.empty() &&
                            static_problem;
    std::vector<ContactNodeState> predicted_sets;
    if (warm_start)
      predicted_sets = previous_contact_states;
    const bool nested = !warm_start && static_problem && !last_adaptation &&
                        start_from_coarser_meshes(predicted_sets);
    const bool predicted_start = warm_start || nested;
    new_contact_solver(parameters.contact,
                       predicted_start ? &predicted_sets : nullptr);
    pcout << "  contact: Newton starts from "
          << (warm_start ? "the previous cycle's contact sets (warm start)" :
              nested     ? "the sets of the coarser meshes (nested iteration)" :
                           "the initial gap")
          << std::endl;
    cycle_record["warm_start"] = warm_start;

    // Where a static solve goes on when it stops with a diagnosis (a
    // ContactDiagnosis; other errors end the run). Sets predicted on
    // another mesh (warm start, nested iteration) can start the iteration
    // on the wrong side of a diagnosis (an all-slip first step), which is
    // not the problem's failure: first the initial gap. Then, if the user
    // scaled c_n = c_t, the natural constants, from the predicted sets and
    // from the initial gap: the solution does not depend on c, only the
    // path of the active set iteration does, and an extreme scale can keep
    // the sets from settling (stability sweep case 241, c x 1e3: 40 steps
    // without convergence from both starts, 31 with c x 1 from the nested
    // sets). A quasi-static path is not restarted: its stick/slip history
    // lives in the solver.
    struct Restart
    {
      parameters::Contact contact;
      bool                from_predicted_sets;
      std::string         description;
      std::string         summary_key;
    };
    std::vector<Restart> restarts;
    if (static_problem && predicted_start)
      restarts.push_back({parameters.contact,
                          false,
                          "from the initial gap",
                          "retried_from_initial_gap"});
    if (static_problem && parameters.contact.complementarity_scale != 1.)
      {
        parameters::Contact natural = parameters.contact;
        natural.complementarity_scale = 1.;
        const std::string constants =
          "with the natural constants c = E_c/h ('Contact/Complementarity "
          "scale' = 1 instead of " +
          Patterns::Tools::Convert<double>::to_string(
            parameters.contact.complementarity_scale) +
          "), from ";
        if (predicted_start)
          restarts.push_back({natural,
                              true,
                              constants + "the predicted sets",
                              "retried_with_natural_complementarity_scale"});
        restarts.push_back({natural,
                            false,
                            constants + "the initial gap",
                            "retried_with_natural_complementarity_scale"});
      }

    // The scene's load path: one step for the static problem, several for
    // a quasi-static one (the solver keeps the stick/slip history).
    const unsigned int  n_steps = scene->n_load_steps();
    ContactSolverReport report;
    unsigned int        total_newton_iterations     = 0;
    unsigned int        restarted_newton_iterations = 0;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        if (n_steps > 1)
          {
            pcout << "  load step " << step << "/" << n_steps << std::endl;
            scene->set_load_step(step);
            // Dirichlet data may follow the load path: new constraints.
            for (auto &body : bodies)
              {
                body->setup_system();
                body->assemble_system();
              }
          }
        for (unsigned int attempt = 0;; ++attempt)
          try
            {
              report = contact_solver->solve();
              break;
            }
          catch (const ContactDiagnosis &e)
            {
              restarted_newton_iterations += e.newton_steps;
              if (attempt == restarts.size())
                {
                  if (attempt == 0)
                    throw;
                  throw ContactDiagnosis(
                    std::string(e.what()) + " (This was the last of " +
                      std::to_string(attempt + 1) +
                      " starts; the log shows how the others stopped.)",
                    e.newton_steps);
                }
              const Restart &restart = restarts[attempt];
              pcout << "  contact: the solve stopped after " << e.newton_steps
                    << " Newton steps (" << std::string(e.what()).substr(0, 160)
                    << " ...); solving again " << restart.description
                    << std::endl;
              cycle_record[restart.summary_key] = true;
              new_contact_solver(restart.contact,
                                 restart.from_predicted_sets ? &predicted_sets :
                                                               nullptr);
            }
        total_newton_iterations += report.newton_iterations;
      }
    report.newton_iterations = total_newton_iterations;
    cycle_record["load_steps"] = n_steps;

    // The initial gap where the bodies face each other: an interference
    // (press) fit starts with an overlap (negative gap), a clearance fit
    // with a positive one. (The solver builds the mortar interface when
    // it solves.)
    {
      const MortarInterface &mortar = contact_solver->mortar_interface();
      double overlap = 0, clearance = 0;
      for (unsigned int j = 0; j < mortar.slave_nodes().size(); ++j)
        if (mortar.is_covered(j))
          {
            const double g = mortar.weighted_initial_gaps()[j] /
                             mortar.slave_weights()[j];
            overlap   = std::max(overlap, -g);
            clearance = std::max(clearance, g);
          }
      pcout << "  contact: initial gap: largest overlap " << overlap
            << " mm, largest clearance " << clearance << " mm" << std::endl;
      cycle_record["initial_overlap"]   = overlap;
      cycle_record["initial_clearance"] = clearance;
    }
    cycle_record["linear_solver"] = {
      {{"method", contact_solver->last_linear_solver_report().method},
       {"iterations",
        contact_solver->last_linear_solver_report().n_iterations}}};
    pcout << "  contact: " << report.newton_iterations
          << " Newton steps, " << report.n_active << " active nodes, "
          << "contact force (" << report.contact_force[0] << ", "
          << report.contact_force[1] << ") N/mm, max pressure "
          << report.max_contact_pressure << " MPa" << std::endl;
    cycle_record["newton_iterations"] = report.newton_iterations;
    if (restarted_newton_iterations > 0)
      cycle_record["newton_iterations_of_stopped_starts"] =
        restarted_newton_iterations;
    cycle_record["converged"]         = report.converged;
    cycle_record["active_nodes"]      = report.n_active;
    cycle_record["stick_nodes"]       = report.n_stick;
    cycle_record["slip_nodes"]        = report.n_slip;
    cycle_record["contact_force"] = {report.contact_force[0],
                                     report.contact_force[1]};
    cycle_record["max_contact_pressure"] = report.max_contact_pressure;
    cycle_record["frictionless"]         = report.frictionless;
    if (report.slave_rotation_free)
      cycle_record["body_1_rotation_free"] = true;
    cycle_record["residual_history"]     = report.residual_history;
    cycle_record["residual_round_off_floor"] =
      report.residual_round_off_floor;
  }



  // Nested iteration (contact/nested_iteration.h) on the first cycle: the
  // bodies are still the scene's meshes with 'Global refinements', so the
  // coarser ones are the same meshes with fewer. Whether it runs, and why
  // not, goes to the log and summary.json.
  bool
  TwoBodyProblem::start_from_coarser_meshes(
    std::vector<ContactNodeState> &predicted_sets)
  {
    const auto &c = parameters.contact;
    const types::global_dof_index n_dofs =
      bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
    const unsigned int n_levels =
      std::min(c.nested_iteration_levels, parameters.mesh.global_refinements);
    nlohmann::json record = {{"levels", nlohmann::json::array()}};
    std::string    skipped;
    if (c.nested_iteration_levels == 0)
      skipped = "switched off ('Contact/Nested iteration levels' = 0)";
    else if (n_levels == 0)
      skipped = "no coarser mesh ('Mesh/Global refinements' = 0)";
    else if (n_dofs <= c.nested_iteration_min_dofs)
      skipped = std::to_string(n_dofs) + " DoFs <= 'Contact/Nested iteration "
                "minimum DoFs' (" + std::to_string(c.nested_iteration_min_dofs) +
                ")";
    if (!skipped.empty())
      {
        pcout << "  contact: nested iteration skipped: " << skipped
              << std::endl;
        record["skipped"]              = skipped;
        cycle_record["nested_iteration"] = record;
        return false;
      }

    std::vector<NestedIterationLevel> levels;
    try
      {
        predicted_sets = predict_contact_sets_on_coarser_meshes(
            mpi_communicator,
            *scene,
            parameters.mesh.cell_type,
            parameters.mesh.global_refinements,
            n_levels,
            parameters.finite_elements,
            parameters.contact,
            parameters.linear_solver,
            levels);
      }
    catch (const std::exception &e)
      {
        // A coarse mesh that does not converge says nothing about the fine
        // one: the fine solve starts cold and decides for itself.
        const std::string what = user_message(e);
        pcout << "  contact: nested iteration abandoned, a coarser solve "
                 "failed: "
              << what << std::endl;
        record["skipped"] = "a coarser solve failed: " + what;
        cycle_record["nested_iteration"] = record;
        return false;
      }
    for (const NestedIterationLevel &l : levels)
      {
        pcout << "  contact: nested iteration, " << l.global_refinements
              << " global refinements: " << l.n_dofs << " DoFs, "
              << l.newton_iterations << " Newton steps, " << l.n_active
              << " active nodes, " << std::setprecision(3) << l.wall_time
              << " s" << std::endl;
        record["levels"].push_back({{"global_refinements", l.global_refinements},
                                    {"n_dofs", l.n_dofs},
                                    {"newton_iterations", l.newton_iterations},
                                    {"active_nodes", l.n_active},
                                    {"wall_time_s", l.wall_time}});
      }
    cycle_record["nested_iteration"] = record;
    return true;
  }



  void
  TwoBodyProblem::solve_separately()
  {
    TimerOutput::Scope t(computing_timer, "solve");
    nlohmann::json     solver_records = nlohmann::json::array();
    for (unsigned int b = 0; b < 2; ++b)
      {
        ElasticBody &body = *bodies[b];
        AssertThrow(!body.is_floating(),
                    ExcMessage(
                      "Body " + std::to_string(b + 1) + " (" + body.name() +
                      ") of scene '" + scene->name() +
                      "' has no Dirichlet support that holds its rigid body "
                      "motions, and the scene has no contact zone that "
                      "could hold it."));
        Timer                    timer;
        const LinearSolverReport report = body.solve(parameters.linear_solver);
        timer.stop();
        pcout << "  " << body.name() << ": solved by " << report.method;
        if (report.method == "cg+amg")
          pcout << " (" << report.n_iterations << " iterations)";
        pcout << " in " << std::setprecision(3) << timer.wall_time() << " s"
              << std::endl;
        solver_records.push_back({{"method", report.method},
                                  {"iterations", report.n_iterations}});
      }
    cycle_record["linear_solver"] = solver_records;
  }



  // The indicator of theory.md section 3: correction, recovery, element
  // contributions and epsilon.
  void
  TwoBodyProblem::estimate_error()
  {
    TimerOutput::Scope t(computing_timer, "error indicator");
    const auto &indicator = parameters.error_indicator;
    const std::array<const ElasticBody *, 2> body_pointers = {
      {bodies[0].get(), bodies[1].get()}};
    error_estimate = std::make_unique<ErrorEstimate>(
      coulomb_adapt::estimate_error(body_pointers,
                                    contact_solver.get(),
                                    parameters.contact.friction_coefficient,
                                    indicator.estimator,
                                    indicator,
                                    parameters.linear_solver,
                                    &computing_timer));
    check_finite_estimate(bodies, *error_estimate);
    compared_estimates.clear();
    // The compared estimators judge the same solution: they take the
    // driving estimator's corrected contact fields instead of solving the
    // corrected problem again.
    if (indicator.compare_estimators)
      for (const ErrorEstimator other : all_error_estimators())
        if (other != indicator.estimator)
          compared_estimates.push_back(
            std::make_unique<ErrorEstimate>(coulomb_adapt::estimate_error(
              body_pointers,
              contact_solver.get(),
              parameters.contact.friction_coefficient,
              other,
              indicator,
              parameters.linear_solver,
              nullptr,
              &error_estimate->correction)));
    const ErrorEstimate &e = *error_estimate;
    if (e.has_contact)
      {
        const auto &c = e.correction;
        if (c.skipped)
          pcout << "  correction: skipped, the FE reactions are in the "
                   "Coulomb cone (corrected fields = FE fields)";
        else
          pcout << "  correction: " << c.n_projected_nodes
                << " nodal reactions projected onto the Coulomb cone, "
                   "relative change "
                << std::scientific << std::setprecision(3)
                << c.relative_change << std::defaultfloat
                << "; corrected problem solved";
        if (c.max_penetration > 0)
          pcout << "; penetration up to " << std::setprecision(3)
                << c.max_penetration << " mm clipped";
        pcout << std::endl;
      }
    if (e.estimator == ErrorEstimator::cre)
      pcout << "  cre: equilibrated stress of degree p + "
            << indicator.cre_degree_increase
            << (e.has_contact ? " from the solution under the consistent "
                                "contact load (solved: the mortar's "
                                "dual-basis traction is not in the cone "
                                "between the nodes)" :
                                "")
            << "; node systems' defect " << std::scientific
            << std::setprecision(1) << e.node_system_defect
            << ", local problems' rigid-motion load " << e.local_problem_defect
            << std::defaultfloat << std::endl;
    auto report = [&](const ErrorEstimate &estimate) {
      pcout << "  error indicator (" << to_string(estimate.estimator)
            << "): epsilon = " << std::fixed << std::setprecision(3)
            << 100 * estimate.epsilon << " % (volume: body 1 "
            << 100 * estimate.epsilon_volume[0] << " %, body 2 "
            << 100 * estimate.epsilon_volume[1] << " %; contact "
            << 100 * estimate.epsilon_contact << " %)" << std::defaultfloat
            << (&estimate == &e ? "" : " [compared, not driving]")
            << std::endl;
    };
    report(e);
    for (const auto &other : compared_estimates)
      report(*other);
    cycle_record["epsilon"]         = e.epsilon;
    cycle_record["epsilon_volume"]  = {e.epsilon_volume[0],
                                      e.epsilon_volume[1]};
    cycle_record["epsilon_contact"] = e.epsilon_contact;
    cycle_record["estimator"]       = to_string(e.estimator);
    if (e.estimator != ErrorEstimator::cre)
      cycle_record["recovery"] = to_string(e.recovery);
    else
      cycle_record["cre"] = {{"degree_increase", indicator.cre_degree_increase},
                             {"node_system_defect", e.node_system_defect},
                             {"local_problem_defect", e.local_problem_defect}};
    if (!compared_estimates.empty())
      {
        auto record_of = [](const ErrorEstimate &estimate) {
          return nlohmann::json{
            {"epsilon", estimate.epsilon},
            {"epsilon_volume",
             {estimate.epsilon_volume[0], estimate.epsilon_volume[1]}},
            {"epsilon_contact", estimate.epsilon_contact},
            {"normalisation_squared", estimate.normalisation_squared}};
        };
        nlohmann::json estimators;
        estimators[to_string(e.estimator)] = record_of(e);
        for (const auto &other : compared_estimates)
          estimators[to_string(other->estimator)] = record_of(*other);
        cycle_record["estimators"] = estimators;
      }
    if (e.has_contact)
      cycle_record["correction"] = {
        {"skipped", e.correction.skipped},
        {"relative_change", e.correction.relative_change},
        {"projected_nodes", e.correction.n_projected_nodes},
        {"max_penetration_clipped", e.correction.max_penetration}};
  }



  // For verification: the exact error of the corrected solution against
  // the scene's exact solution, or else a reference solution: this cycle's
  // meshes refined `Reference refinements` more times (theory.md section
  // 8), with its own error and the energy check.
  void
  TwoBodyProblem::compare_with_exact_error(const unsigned int)
  {
    TimerOutput::Scope t(computing_timer, "exact error");
    const std::array<const ElasticBody *, 2> body_pointers = {
      {bodies[0].get(), bodies[1].get()}};
    std::unique_ptr<ReferenceStress>         exact;
    const ReferenceSolutionStress *          reference_solution = nullptr;
    if (bodies[0]->description().exact_displacement &&
        bodies[1]->description().exact_displacement)
      exact = std::make_unique<ExactSolutionStress>(body_pointers);
    else
      {
        const unsigned int r = parameters.error_indicator.reference_refinements;
        pcout << "  exact error: solving the reference problem (this cycle's "
                 "meshes refined "
              << r << " times) and, for its own error, "
              << (r > 1 ? "the same refined " + std::to_string(r - 1) +
                            " times" :
                          std::string("comparing it with this cycle's "
                                      "solution"))
              << std::endl;
        auto solution = std::make_unique<ReferenceSolutionStress>(
          *scene, parameters, body_pointers, r);
        reference_solution = solution.get();
        exact              = std::move(solution);
      }
    const ExactErrorComparison c = coulomb_adapt::compare_with_exact_error(
      body_pointers, *error_estimate, *exact);
    pcout << "  exact error (" << exact->description()
          << "): epsilon_exact = " << std::fixed << std::setprecision(3)
          << 100 * c.epsilon_exact << " %, effectivity " << c.effectivity
          << " (elements: mean " << c.element_effectivity_mean << ", std "
          << c.element_effectivity_std << ", min "
          << c.element_effectivity_min << ", max "
          << c.element_effectivity_max << ")" << std::defaultfloat
          << std::endl;
    cycle_record["epsilon_exact"] = c.epsilon_exact;
    cycle_record["effectivity"]   = c.effectivity;
    cycle_record["element_effectivity"] = {
      {"mean", c.element_effectivity_mean},
      {"std", c.element_effectivity_std},
      {"min", c.element_effectivity_min},
      {"max", c.element_effectivity_max},
      {"n_elements", c.n_elements}};
    cycle_record["exact_error_reference"] = exact->description();
    // Compared estimators: each against the exact error of its own
    // corrected solution (the field it estimates).
    if (!compared_estimates.empty())
      {
        auto add_effectivity = [&](const ErrorEstimate &        estimate,
                                   const ExactErrorComparison &x) {
          cycle_record["estimators"][to_string(estimate.estimator)].update(
            {{"epsilon_exact", x.epsilon_exact},
             {"effectivity", x.effectivity},
             {"element_effectivity",
              {{"mean", x.element_effectivity_mean},
               {"std", x.element_effectivity_std},
               {"min", x.element_effectivity_min},
               {"max", x.element_effectivity_max},
               {"n_elements", x.n_elements}}}});
          pcout << "  exact error of " << to_string(estimate.estimator)
                << "'s corrected solution: " << std::fixed
                << std::setprecision(3) << 100 * x.epsilon_exact
                << " %, effectivity " << x.effectivity << std::defaultfloat
                << std::endl;
        };
        add_effectivity(*error_estimate, c);
        for (const auto &other : compared_estimates)
          add_effectivity(*other,
                          coulomb_adapt::compare_with_exact_error(body_pointers,
                                                                  *other,
                                                                  *exact));
      }
    if (reference_solution == nullptr)
      return;

    // The energy check: e^2 = 2 (U_ref - U_h) for the FE solution of a
    // linear, load-driven problem (with frictionless contact nearly: the
    // contact work vanishes at the solution); with the seed's
    // normalisation D^2 ~ 8 U that is epsilon ~ sqrt((U_ref - U_h) /
    // (4 U_ref)).
    double energy = 0, reference_energy = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        energy += strain_energy(*bodies[b], bodies[b]->solution());
        reference_energy += reference_solution->strain_energy(b);
      }
    const double epsilon_energy =
      std::sqrt(std::max(0., reference_energy - energy) /
                std::max(4 * reference_energy, 1e-300));
    pcout << "  exact error: reference's own error " << std::fixed
          << std::setprecision(3) << 100 * reference_solution->own_error()
          << " % (from the energies "
          << 100 * reference_solution->own_error_from_energy()
          << " %); energy check: epsilon_energy = " << 100 * epsilon_energy
          << " % (strain energy " << std::scientific << energy
          << ", reference " << reference_energy << ")" << std::defaultfloat
          << std::endl;
    cycle_record["exact_error_reference_error"] =
      reference_solution->own_error();
    cycle_record["exact_error_reference_error_energy"] =
      reference_solution->own_error_from_energy();
    cycle_record["exact_error_reference_dofs"] = reference_solution->n_dofs();
    cycle_record["reference_strain_energy"] = {
      reference_solution->strain_energy(0),
      reference_solution->strain_energy(1)};
    cycle_record["epsilon_energy"] = epsilon_energy;
  }



  void
  TwoBodyProblem::output_results(const unsigned int cycle,
                                 const bool         last_cycle)
  {
    TimerOutput::Scope t(computing_timer, "output");
    // The contact CSV is small and always written; the fields on request.
    const std::string &write_cycles = parameters.output.write_cycles;
    const bool         write_fields =
      write_cycles == "all" || (write_cycles == "last" && last_cycle);
    if (contact_solver)
      contact_output->write(contact_solver->node_states(),
                            error_estimate ?
                              error_estimate->contact.nodal_density :
                              std::vector<double>(),
                            cycle,
                            write_fields);
    if (!write_fields)
      return;
    for (unsigned int b = 0; b < 2; ++b)
      {
        BodyErrorFields fields;
        if (error_estimate)
          fields = {&error_estimate->indicator[b],
                    &error_estimate->density[b],
                    error_estimate->recovered[b].get()};
        body_outputs[b]->write(*bodies[b], cycle, fields);
      }
  }



  void
  TwoBodyProblem::refine_grid()
  {
    TimerOutput::Scope t(computing_timer, "adapt mesh");
    // What lives on the old meshes goes; the contact sets are kept by
    // position for the warm start.
    compared_estimates.clear();
    previous_contact_states.clear();
    if (contact_solver)
      previous_contact_states = contact_solver->node_states();
    contact_solver.reset();
    const auto &a = parameters.adaptation;
    last_adaptation =
      adapt_meshes({{bodies[0].get(), bodies[1].get()}},
                   *error_estimate,
                   previous_contact_states,
                   a,
                   parameters.finite_elements.degree,
                   target_calibration.aim(a.target_error));
    if (last_adaptation->predicted_epsilon > 0)
      target_calibration.record_plan(last_adaptation->predicted_epsilon);
    error_estimate.reset();
    const MeshAdaptationReport &r = *last_adaptation;
    pcout << "  adapt (" << r.strategy;
    if (r.strategy == "refine")
      pcout << ", " << a.refinement_criterion;
    pcout << "): ";
    if (r.predicted_n_cells >= 0)
      pcout << "optimal mesh for epsilon_0 = " << 100 * a.target_error
            << " %, planned for " << std::setprecision(3)
            << 100 * r.aimed_epsilon << " % (safety factor "
            << a.target_safety_factor << ", measured/predicted "
            << target_calibration.correction()
            << "): N* = " << std::llround(r.predicted_n_cells)
            << " cells, predicted epsilon " << std::setprecision(3)
            << 100 * r.predicted_epsilon << " % (r_E bounded to ["
            << a.min_size_ratio << " (" << lowest_size_ratio(a.min_size_ratio, true)
            << " at singular points), " << a.max_size_ratio << "]: "
            << r.n_at_min_ratio << " cells at the lower, "
            << r.n_at_max_ratio << " at the upper bound; q reduced to "
            << std::min<double>(parameters.finite_elements.degree,
                                a.singular_rate)
            << " in " << r.n_singular_cells << " cells at singular points)";
    if (r.limited_by_max_dofs)
      pcout << "; more cells than 'Maximum number of DoFs' = " << a.max_dofs
            << " allows: the optimal mesh of that size instead (predicted "
               "epsilon above epsilon_0)";
    if (r.strategy == "refine")
      pcout << (r.predicted_n_cells >= 0 ? "; " : "") << r.n_refine_flags
            << " cells flagged for refinement, " << r.n_coarsen_flags
            << " for coarsening";
    if (r.strategy == "uniform")
      pcout << "every cell refined once";
    pcout << std::endl;
  }



  bool
  TwoBodyProblem::continue_cycles(const unsigned int            cycle,
                                  const types::global_dof_index n_dofs,
                                  std::string &                 reason) const
  {
    const auto &a = parameters.adaptation;
    std::ostringstream s;
    // An over-refined mesh is optimised again only while a further cycle
    // could still refine it should the coarser one miss the target.
    const bool over_refined =
      a.strategy == "remesh" && error_estimate &&
      error_estimate->epsilon < a.over_refinement_ratio * a.target_error &&
      cycle + 2 < a.n_cycles && n_dofs < a.max_dofs;
    if (over_refined && error_estimate->epsilon <= a.target_error)
      pcout << "  over-refined: epsilon = " << std::setprecision(4)
            << 100 * error_estimate->epsilon << " % < "
            << a.over_refinement_ratio << " epsilon_0: optimising again"
            << std::endl;
    if (a.target_error > 0 && error_estimate &&
        error_estimate->epsilon <= a.target_error && cycle + 1 >= a.min_cycles &&
        !over_refined)
      s << "target reached: epsilon = " << std::setprecision(4)
        << 100 * error_estimate->epsilon << " % <= epsilon_0 = "
        << 100 * a.target_error << " %";
    else if (cycle + 1 >= a.n_cycles)
      {
        s << "maximum number of cycles (" << a.n_cycles << ") reached";
        if (a.target_error > 0 && error_estimate)
          s << " before the target: epsilon = " << std::setprecision(4)
            << 100 * error_estimate->epsilon << " % > epsilon_0 = "
            << 100 * a.target_error << " %";
      }
    else if (n_dofs >= a.max_dofs)
      s << "maximum number of DoFs reached (" << n_dofs << " >= " << a.max_dofs
        << ")";
    reason = s.str();
    return reason.empty();
  }



  // Unbounded work is refused before it starts: the first meshes' DoFs,
  // estimated from the coarse meshes (each uniform refinement multiplies
  // the cells by 4; a P_p mesh has about p^2 vertices' worth of DoFs per
  // quadrilateral, half that per triangle), must stay below the limit the
  // adaptation keeps to. Before: 'Global refinements = 12' ended in
  // std::bad_alloc after minutes.
  void
  TwoBodyProblem::check_initial_mesh_size() const
  {
    const unsigned int p = parameters.finite_elements.degree;
    double             estimate = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        Triangulation<2> coarse;
        scene->create_coarse_mesh(b, parameters.mesh.cell_type, coarse);
        // Degenerate cells, named with the file they come from (ElasticBody
        // checks every mesh it builds again, remeshed ones too).
        try
          {
            check_mesh_cells(coarse, scene->describe_body(b).name, b);
          }
        catch (const std::exception &e)
          {
            throw ParameterError(mesh_source + e.what());
          }
        const double per_cell =
          (coarse.all_reference_cells_are_hyper_cube() ? 2. : 1.) * p * p;
        const double n_cells = coarse.n_active_cells() *
                               std::pow(4., parameters.mesh.global_refinements);
        estimate += n_cells * per_cell;
        // The recovered stress of a single cell (its projection onto the
        // continuous space, or its patch fit) is the finite element stress
        // itself: the zz/spr indicator would be 0 whatever the error
        // (blocks with 1 x 1 subdivisions: epsilon = 0 %, exact 15.6 %).
        if (n_cells == 1 &&
            parameters.error_indicator.estimator != ErrorEstimator::cre)
          throw ParameterError(
            "Mesh/Global refinements",
            std::to_string(parameters.mesh.global_refinements),
            "body " + std::to_string(b + 1) + " (" +
              scene->describe_body(b).name +
              ") would have a single cell, on which the recovered stress "
              "of the '" + to_string(parameters.error_indicator.estimator) +
              "' estimator is the finite element stress itself: the "
              "error indicator would be 0 whatever the error. Give the "
              "body more cells (the scene's subdivisions) or refine once");
      }
    // The multipliers are differences of body 1's nodal forces, whose
    // terms are E1 / E_c times the contact force: their round-off, n eps
    // E1 / E_c of the pressure, reaches the largest 'Contact/Tolerance'
    // (1e-6) at a ratio of about 1e8 (E1 = 1e30 on the blocks: a wrong
    // "would slide"). Body 2 may be the stiff one.
    const BodyDescription body_1 = scene->describe_body(0);
    const BodyDescription body_2 = scene->describe_body(1);
    const double          E1     = body_1.material.youngs_modulus;
    const double          E2     = body_2.material.youngs_modulus;
    if (body_1.contact_boundary_id != numbers::invalid_boundary_id &&
        body_2.contact_boundary_id != numbers::invalid_boundary_id &&
        E1 / E2 > 1e8)
      {
        std::ostringstream s;
        s << std::setprecision(3) << "body 1's Young's modulus (" << E1
          << " MPa) is " << E1 / E2 << " times body 2's (" << E2
          << " MPa): the contact pressures are differences of body 1's "
             "nodal forces, which would lose all their digits above a ratio "
             "of 1e8. Make the stiffer body body 2 (the lower one), or use "
             "moduli closer to each other";
        throw ParameterError(s.str());
      }
    // Nearly incompressible bodies lock with P1 elements: the displacement
    // comes out too small and the indicator measures the locked solution.
    for (const BodyDescription *d : {&body_1, &body_2})
      if (d->material.poissons_ratio > 0.49 && p == 1)
        pcout << "warning: " << d->name << " has Poisson's ratio "
              << d->material.poissons_ratio
              << ": nearly incompressible, it locks with linear elements "
                 "(displacements too small, stresses oscillating); use "
                 "'Finite elements/Polynomial degree' = 2"
              << std::endl;
    if (estimate > parameters.adaptation.max_dofs)
      {
        std::ostringstream s;
        s << "the first meshes would have about " << std::setprecision(3)
          << estimate << " DoFs, above 'Adaptation/Maximum number of DoFs' ("
          << parameters.adaptation.max_dofs
          << "): lower it, or raise that limit if the machine has the "
             "memory (about 1 kB per DoF)";
        throw ParameterError("Mesh/Global refinements",
                             std::to_string(parameters.mesh.global_refinements),
                             s.str());
      }
  }



  // A run into the directory of an earlier, longer one would leave that
  // run's later cycles beside this run's summary.json, as if they were
  // its own. The program's own per-cycle files (and the .pvd lists) go
  // before the first cycle; other files stay.
  void
  TwoBodyProblem::remove_files_of_earlier_run() const
  {
    unsigned int n_removed = 0;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        const std::regex own_file(
          "(body-[12]|contact)(_[0-9]{3}(\\.[0-9]+)?\\.(vtu|pvtu|csv)|\\.pvd)"
          "(\\.tmp)?");
        std::error_code error;
        for (const auto &entry : std::filesystem::directory_iterator(
               parameters.output.directory, error))
          if (entry.is_regular_file(error) &&
              std::regex_match(entry.path().filename().string(), own_file))
            n_removed += std::filesystem::remove(entry.path(), error);
      }
    n_removed = Utilities::MPI::broadcast(mpi_communicator, n_removed, 0);
    if (n_removed > 0)
      pcout << "  removed " << n_removed
            << " output files of an earlier run from '"
            << parameters.output.directory << "'" << std::endl;
  }



  void
  TwoBodyProblem::run()
  {
    pcout << "coulomb-adapt: scene '" << scene->name() << "', "
          << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " MPI rank(s), results in '" << parameters.output.directory
          << "'" << std::endl;
    remove_files_of_earlier_run();

    {
      TimerOutput::Scope t(computing_timer, "setup");
      for (unsigned int b = 0; b < 2; ++b)
        {
          bodies[b] = std::make_unique<ElasticBody>(
            mpi_communicator,
            *scene,
            b,
            parameters.mesh.cell_type,
            parameters.mesh.global_refinements,
            parameters.finite_elements);
          body_outputs[b] = std::make_unique<BodyOutput>(
            parameters.output.directory,
            "body-" + std::to_string(b + 1),
            parameters.output.format);
        }
      contact_output = std::make_unique<ContactOutput>(
        parameters.output.directory,
        mpi_communicator,
        parameters.output.format);
    }
    // Before any solve: the exact error needs something to compare with.
    AssertThrow(!parameters.error_indicator.compute_exact_error ||
                  (bodies[0]->description().exact_displacement &&
                   bodies[1]->description().exact_displacement) ||
                  (has_contact() && scene->n_load_steps() == 1),
                ExcMessage("Error indicator/Compute exact error: scene '" +
                           scene->name() +
                           "' has no exact solution, and a reference "
                           "solution is computed only for static contact "
                           "scenes."));

    for (unsigned int cycle = 0; cycle < parameters.adaptation.n_cycles;
         ++cycle)
      {
        Timer      cycle_timer;
        const auto times_before =
          computing_timer.get_summary_data(TimerOutput::total_wall_time);
        cycle_record = {{"cycle", cycle}};
        if (cycle > 0)
          refine_grid();

        setup_system();
        pcout << "Cycle " << cycle << std::endl;
        cycle_record["strategy"] = parameters.adaptation.strategy;
        types::global_dof_index n_dofs = 0;
        nlohmann::json          body_records = nlohmann::json::array();
        for (const auto &body : bodies)
          {
            const auto n_cells    = body->triangulation().n_global_active_cells();
            const auto n_vertices = body->n_vertices();
            const auto n_body_dofs = body->dof_handler().n_dofs();
            n_dofs += n_body_dofs;
            pcout << "  " << body->name() << ": " << n_cells << " cells, "
                  << n_vertices << " vertices, " << n_body_dofs << " DoFs ("
                  << body->dof_handler().get_fe().get_name() << ")"
                  << std::endl;
            body_records.push_back({{"name", body->name()},
                                    {"n_cells", n_cells},
                                    {"n_vertices", n_vertices},
                                    {"n_dofs", n_body_dofs}});
          }
        if (last_adaptation && last_adaptation->predicted_n_cells >= 0)
          {
            const double obtained =
              bodies[0]->triangulation().n_global_active_cells() +
              bodies[1]->triangulation().n_global_active_cells();
            pcout << "  cells: " << std::llround(obtained) << " obtained, N* = "
                  << std::llround(last_adaptation->predicted_n_cells)
                  << " predicted (" << std::showpos << std::setprecision(3)
                  << 100 * (obtained / last_adaptation->predicted_n_cells - 1)
                  << std::noshowpos << " %)" << std::endl;
            cycle_record["adaptation"] = {
              {"predicted_n_cells", last_adaptation->predicted_n_cells},
              {"predicted_epsilon", last_adaptation->predicted_epsilon},
              {"aimed_epsilon", last_adaptation->aimed_epsilon},
              {"calibration", target_calibration.correction()},
              {"obtained_n_cells", obtained},
              {"singular_cells", last_adaptation->n_singular_cells},
              {"limited_by_max_dofs", last_adaptation->limited_by_max_dofs}};
          }
        if (last_adaptation && last_adaptation->strategy == "refine")
          {
            cycle_record["adaptation"]["refine_flags"] =
              last_adaptation->n_refine_flags;
            cycle_record["adaptation"]["coarsen_flags"] =
              last_adaptation->n_coarsen_flags;
          }
        if (scene->n_load_steps() > 1)
          scene->set_load_step(1);
        assemble_system();
        solve();
        estimate_error();
        target_calibration.record_achieved(error_estimate->epsilon);
        // Timed on its own: a verification cost, not the indicator's.
        if (parameters.error_indicator.compute_exact_error)
          compare_with_exact_error(cycle);

        for (unsigned int b = 0; b < 2; ++b)
          if (bodies[b]->description().exact_displacement)
            {
              const ElasticityErrors e = compute_elasticity_errors(
                *bodies[b], *bodies[b]->description().exact_displacement);
              pcout << "  " << bodies[b]->name()
                    << ": error against the exact solution: L2 "
                    << std::scientific << std::setprecision(3) << e.l2
                    << " mm, energy " << e.energy << " (relative "
                    << e.energy / e.energy_of_exact << ")" << std::defaultfloat
                    << std::endl;
              body_records[b]["exact_error"] = {
                {"l2", e.l2},
                {"energy", e.energy},
                {"relative_energy", e.energy / e.energy_of_exact}};
            }
        for (unsigned int b = 0; b < 2; ++b)
          body_records[b]["strain_energy"] =
            strain_energy(*bodies[b], bodies[b]->solution());
        // Decided before the output: 'Write cycles = last' writes the
        // fields of the cycle after which the adaptation stops.
        std::string reason;
        const bool  last_cycle = !continue_cycles(cycle, n_dofs, reason);
        output_results(cycle, last_cycle);

        cycle_timer.stop();
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        cycle_record["bodies"]      = body_records;
        cycle_record["n_dofs"]      = n_dofs;
        cycle_record["wall_time_s"] = cycle_timer.wall_time();
        // Per-phase wall times of this cycle (rank 0's clock).
        nlohmann::json timings;
        for (const auto &[section, total] :
             computing_timer.get_summary_data(TimerOutput::total_wall_time))
          {
            const auto before = times_before.find(section);
            timings[section] =
              total - (before == times_before.end() ? 0. : before->second);
          }
        cycle_record["timings_s"] = timings;
        // Peak resident memory so far: largest rank, and all ranks together.
        cycle_record["peak_memory_MiB"] =
          Utilities::MPI::max(memory.VmHWM / 1024., mpi_communicator);
        cycle_record["peak_memory_total_MiB"] =
          Utilities::MPI::sum(memory.VmHWM / 1024., mpi_communicator);
        summary->add_cycle(cycle_record);

        // The per-cycle line a user watches, and the final table's row.
        const double       epsilon = error_estimate->epsilon;
        const unsigned int newton =
          cycle_record.value("newton_iterations", 0u);
        pcout << "Cycle " << cycle << ": " << n_dofs << " DoFs, epsilon = "
              << std::fixed << std::setprecision(3) << 100 * epsilon
              << " %, epsilon_contact = "
              << 100 * error_estimate->epsilon_contact << " %"
              << std::defaultfloat;
        if (contact_solver)
          pcout << ", " << newton << " Newton steps";
        pcout << ", " << std::setprecision(3) << cycle_timer.wall_time()
              << " s" << std::endl;
        cycle_table.add_value("cycle", cycle);
        cycle_table.add_value("cells 1", body_records[0]["n_cells"].get<unsigned int>());
        cycle_table.add_value("cells 2", body_records[1]["n_cells"].get<unsigned int>());
        cycle_table.add_value("DoFs", n_dofs);
        cycle_table.add_value("eps %", 100 * epsilon);
        cycle_table.add_value("eps_c %", 100 * error_estimate->epsilon_contact);
        if (contact_solver)
          cycle_table.add_value("Newton", newton);
        cycle_table.add_value("time s", cycle_timer.wall_time());

        if (last_cycle)
          {
            pcout << "Adaptation stops after cycle " << cycle << ": "
                  << reason << std::endl;
            summary->set("stop_reason", reason);
            break;
          }
      }
    for (const std::string column : {"eps %", "eps_c %", "time s"})
      cycle_table.set_precision(column, 3);
    for (const std::string column : {"eps %", "eps_c %"})
      cycle_table.set_scientific(column, false);
    if (pcout.is_active())
      {
        pcout.get_stream() << std::endl;
        cycle_table.write_text(pcout.get_stream(),
                               TableHandler::org_mode_table);
      }
    computing_timer.print_summary();
    pcout << "(the 'error indicator: ...' sections are parts of 'error "
             "indicator': the percentages add up to more than 100)"
          << std::endl;
  }
} // namespace coulomb_adapt
