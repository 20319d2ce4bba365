#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <coulomb_adapt/app/finiteness.h>
#include <coulomb_adapt/app/preflight_checks.h>
#include <coulomb_adapt/app/target_claim.h>
#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/bodies/elasticity_errors.h>
#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/core/units.h>
#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/output/file_writer.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include <cmath>
#include <filesystem>

namespace coulomb_adapt
{
  namespace
  {
    // Whether two bodies so described touch: both name a contact
    // boundary (the manufactured scene's do not).
    bool
    describe_contact(const BodyDescription &a, const BodyDescription &b)
    {
      return a.contact_boundary_id != numbers::invalid_boundary_id &&
             b.contact_boundary_id != numbers::invalid_boundary_id;
    }
  } // namespace



  void
  TwoBodyProblem::declare_parameters(ParameterHandler &prm)
  {
    Parameters::declare_parameters(prm);
    scenes::declare_parameters(prm);
  }



  TwoBodyProblem::TwoBodyProblem(const MPI_Comm     mpi_communicator,
                                 const Parameters  &parameters,
                                 ParameterHandler  &prm,
                                 const std::string &parameter_file,
                                 std::ostream      &log)
    : mpi_communicator(mpi_communicator)
    , parameters(parameters)
    , pcout(log, Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    // No communicator: the timer's destructor must not synchronise the
    // ranks while an exception unwinds (that could deadlock).
    , computing_timer(pcout, TimerOutput::never, TimerOutput::wall_times)
    , target_calibration(parameters.adaptation.target_safety_factor)
  {
    scene =
      std::make_unique<ScaledScene>(scenes::create_scene(parameters, prm));
    mesh_source = scene->mesh_source();
    // Before summary.json is begun: a run refused here, like any other
    // error in the parameters, leaves no summary without a status.
    check_before_meshing(*scene, parameters, mesh_source, pcout);
    cycle_report = std::make_unique<CycleReport>(mpi_communicator,
                                                 pcout,
                                                 computing_timer,
                                                 parameters.output.directory +
                                                   "/summary.json",
                                                 scene->name(),
                                                 parameter_file);
    if (!scene->reference_values().empty())
      cycle_report->set_run_entry("reference", scene->reference_values());
    // A scene without contact (manufactured) has no friction: no entry,
    // rather than the parameter file's value, which nothing there uses
    // (and not null, which summary.json keeps for numbers that failed).
    if (describe_contact(scene->describe_body(0), scene->describe_body(1)))
      cycle_report->set_run_entry("friction_coefficient",
                                  parameters.contact.friction_coefficient);
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
    return describe_contact(bodies[0]->description(), bodies[1]->description());
  }



  // Both bodies coupled through the mortar contact interface; the driver
  // chooses the start and the restarts and runs the load path.
  void
  TwoBodyProblem::solve_contact()
  {
    TimerOutput::Scope  t(computing_timer, "contact solve");
    ContactSolveOutcome outcome =
      contact_solve_driver->solve(previous_contact_states, !last_adaptation);
    contact_solver = std::move(outcome.solver);
    if (contact_solver)
      contact_solver->release_newton_system();
    cycle_report->record_contact_solve(outcome);
  }



  void
  TwoBodyProblem::solve_separately()
  {
    TimerOutput::Scope t(computing_timer, "solve");
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
        cycle_report->record_linear_solve(body, report, timer.wall_time());
      }
  }



  // The indicator of theory.md section 3: correction, recovery, element
  // contributions and epsilon.
  void
  TwoBodyProblem::estimate_error()
  {
    TimerOutput::Scope   t(computing_timer, "error indicator");
    const auto          &indicator = parameters.error_indicator;
    ErrorEstimateOptions options;
    options.timer  = &computing_timer;
    error_estimate = std::make_unique<ErrorEstimate>(
      coulomb_adapt::estimate_error(body_pointers(),
                                    contact_solver.get(),
                                    parameters.contact.friction_coefficient,
                                    indicator.estimator,
                                    indicator,
                                    parameters.linear_solver,
                                    options));
    check_finite_estimate(bodies, *error_estimate);
    // The compared estimators judge the same solution: they take the
    // driving estimator's corrected contact fields instead of solving the
    // corrected problem again.
    compared_estimates.clear();
    std::vector<const ErrorEstimate *> compared;
    if (indicator.compare_estimators)
      for (const ErrorEstimator other : all_error_estimators())
        if (other != indicator.estimator)
          {
            ErrorEstimateOptions known;
            known.known_correction = &error_estimate->correction;
            compared_estimates.push_back(
              std::make_unique<ErrorEstimate>(coulomb_adapt::estimate_error(
                body_pointers(),
                contact_solver.get(),
                parameters.contact.friction_coefficient,
                other,
                indicator,
                parameters.linear_solver,
                known)));
            compared.push_back(compared_estimates.back().get());
          }
    cycle_report->record_error_estimate(*error_estimate,
                                        compared,
                                        indicator.cre_degree_increase);
  }



  // For verification: the exact error of the corrected solution against
  // the scene's exact solution, or else a reference solution: this cycle's
  // meshes refined `Reference refinements` more times (theory.md section
  // 8), with its own error and the energy check. Compared estimators are
  // each measured against the exact error of their own corrected solution
  // (the field they estimate).
  void
  TwoBodyProblem::compare_with_exact_error(
    const std::array<double, 2> &strain_energies)
  {
    TimerOutput::Scope               t(computing_timer, "exact error");
    std::unique_ptr<ReferenceStress> exact;
    const ReferenceSolutionStress   *reference_solution = nullptr;
    if (bodies[0]->description().exact_displacement &&
        bodies[1]->description().exact_displacement)
      exact = std::make_unique<ExactSolutionStress>(body_pointers());
    else
      {
        const unsigned int r = parameters.error_indicator.reference_refinements;
        cycle_report->announce_reference_solution(r);
        auto solution = std::make_unique<ReferenceSolutionStress>(
          *scene, parameters, body_pointers(), r);
        reference_solution = solution.get();
        exact              = std::move(solution);
      }
    std::vector<std::pair<ErrorEstimator, ExactErrorComparison>> comparisons;
    comparisons.emplace_back(error_estimate->estimator,
                             coulomb_adapt::compare_with_exact_error(
                               body_pointers(), *error_estimate, *exact));
    for (const auto &other : compared_estimates)
      comparisons.emplace_back(other->estimator,
                               coulomb_adapt::compare_with_exact_error(
                                 body_pointers(), *other, *exact));
    cycle_report->record_exact_error(exact->description(), comparisons);
    if (reference_solution == nullptr)
      return;

    // The energy check: e^2 = 2 (U_ref - U_h) for the FE solution of a
    // linear, load-driven problem (with frictionless contact nearly: the
    // contact work vanishes at the solution), e^2 = 2 (U_h - U_ref) for a
    // displacement-driven one (prescribed displacements or overlap: the
    // FE solution's energy lies above); with the seed's normalisation D^2
    // ~ 8 U that is epsilon ~ sqrt(|U_ref - U_h| / (4 U_ref)). (Clipped
    // at 0, the press fit's check printed 0 against epsilon_exact =
    // 0.037 %.) Neither holds for a mix of the two.
    const double energy           = strain_energies[0] + strain_energies[1];
    const double reference_energy = reference_solution->strain_energy(0) +
                                    reference_solution->strain_energy(1);
    const double epsilon_energy =
      std::sqrt(std::abs(reference_energy - energy) /
                std::max(4 * reference_energy, 1e-300));
    cycle_report->record_reference_solution(*reference_solution,
                                            energy,
                                            reference_energy,
                                            epsilon_energy);
  }



  TargetClaim
  TwoBodyProblem::target_claim() const
  {
    // Without contact (the manufactured scene) the friction coefficient
    // of the parameter file plays no part: the bound is that of linear
    // elasticity.
    return make_target_claim(error_estimate->estimator,
                             has_contact() ?
                               parameters.contact.friction_coefficient :
                               0.,
                             cycle_report->exact_error(),
                             error_estimate->misses_held_reaction(),
                             parameters.finite_elements.degree,
                             error_estimate->relaxed_equilibration[0] ||
                               error_estimate->relaxed_equilibration[1],
                             error_estimate->evaluation_degree_increase,
                             error_estimate->penetration_after > 0,
                             error_estimate->negative_pressure > 1e-8,
                             error_estimate->displacement_data_unlifted);
  }



  // Computed once: the energy check of compare_with_exact_error() uses
  // the same values.
  std::array<double, 2>
  TwoBodyProblem::record_strain_energies()
  {
    std::array<double, 2> energies;
    for (unsigned int b = 0; b < 2; ++b)
      {
        energies[b] = strain_energy(*bodies[b], bodies[b]->solution());
        cycle_report->record_strain_energy(b, energies[b]);
      }
    return energies;
  }



  // Each body's error against its exact displacement, where the scene has
  // one.
  void
  TwoBodyProblem::compare_with_exact_displacements()
  {
    for (unsigned int b = 0; b < 2; ++b)
      if (bodies[b]->description().exact_displacement)
        cycle_report->record_body_error(
          b,
          *bodies[b],
          compute_elasticity_errors(
            *bodies[b], *bodies[b]->description().exact_displacement));
  }



  void
  TwoBodyProblem::output_results(const unsigned int cycle,
                                 const bool         last_cycle)
  {
    TimerOutput::Scope t(computing_timer, "output");
    // The contact CSV is small and always written; the fields on request.
    const WriteCycles write_cycles = parameters.output.write_cycles;
    const bool        write_fields = write_cycles == WriteCycles::all ||
                              (write_cycles == WriteCycles::last && last_cycle);
    // The physical values of a scaled problem: stresses and lengths of the
    // deformation times P, the contact term's density (MPa mm) times P^2,
    // where doubles hold them (the CSV). The fields (VTU and HDF5) go
    // through deal.II's patches, whose 32-bit floats (1e-38 ... 3e38)
    // would not hold the physical fields of a scaled problem: they get the
    // fields of the scaled problem (HDF5 got the physical ones, which
    // came out inf).
    const units::Scales scales = scene->scales();
    const bool          scaled = scales.stress != 1 || scales.displacement != 1;
    const bool          scaled_fields = scaled && write_fields;
    if (scaled_fields)
      cycle_report->report_scaled(
        parameters.output.format == OutputFormat::hdf5 ? "HDF5 fields" :
                                                         "VTU fields",
        scales.stress == scales.displacement ?
          "32-bit floats cannot hold them; multiply displacement, stresses, "
          "smoothed stresses, contact_pressure, tangential_traction, gap and "
          "slip by load_scale, contact_error_density by its square" :
          "32-bit floats cannot hold them; multiply stresses, smoothed "
          "stresses, contact_pressure and tangential_traction by "
          "load_scale, displacement, gap and slip by displacement_scale, "
          "contact_error_density by both");
    // The bodies' fields first, their indexes last: if any file fails, no
    // index lists a cycle whose files are missing (contact.pvd did, and
    // body 1's .pvd when body 2's file failed; found by walkthroughs).
    // The earlier cycle's fields, if written in the background, are
    // completed and indexed first: one cycle at a time, and indexed
    // whatever happens to this cycle's.
    if (complete_background_writes())
      write_field_indexes();
    const bool in_background =
      parameters.output.write_in_background && !last_cycle;
    if (write_fields)
      for (unsigned int b = 0; b < 2; ++b)
        {
          BodyErrorFields fields;
          if (error_estimate)
            fields = {&error_estimate->indicator[b],
                      &error_estimate->density[b],
                      parameters.output.write_smoothed_stress ?
                        error_estimate->recovered[b].get() :
                        nullptr};
          body_outputs[b]->write(*bodies[b], cycle, fields, in_background);
          if (!in_background && b == 1)
            fields_complete_through = cycle;
        }
    if (contact_solver)
      {
        const std::vector<ContactNodeState> &scaled_states =
          contact_solver->node_states();
        const std::vector<double> scaled_density =
          error_estimate ? error_estimate->contact.nodal_density :
                           std::vector<double>();
        std::vector<ContactNodeState> states  = scaled_states;
        std::vector<double>           density = scaled_density;
        if (scaled)
          {
            for (ContactNodeState &s : states)
              {
                for (double *x : {&s.pressure, &s.tangential_traction})
                  *x = cycle_report->physical(*x,
                                              units::Kind::stress,
                                              "contact CSV");
                for (double *x : {&s.gap, &s.slip})
                  *x = cycle_report->physical(*x,
                                              units::Kind::displacement,
                                              "contact CSV");
              }
            for (double &d : density)
              d = cycle_report->physical(d,
                                         units::Kind::energy,
                                         "contact_error_density");
          }
        contact_output->write(states,
                              density,
                              cycle,
                              write_fields,
                              scaled_fields ? &scaled_states : nullptr,
                              scaled_fields ? &scaled_density : nullptr);
      }
    if (write_fields)
      write_field_indexes();
  }



  // Both bodies' or neither's: a body whose pieces are complete is not
  // indexed when the other's failed (finish() throws on every rank
  // together, so this stays collective).
  bool
  TwoBodyProblem::complete_background_writes()
  {
    std::array<std::optional<std::pair<unsigned int, std::string>>, 2> records;
    std::string                                                        error;
    for (unsigned int b = 0; b < 2; ++b)
      if (body_outputs[b])
        try
          {
            records[b] =
              body_outputs[b]->finish_background_write(mpi_communicator);
          }
        catch (const std::exception &e)
          {
            if (error.empty())
              error = user_message(e);
          }
    AssertThrow(error.empty(), ExcMessage(error));
    bool completed = false;
    for (unsigned int b = 0; b < 2; ++b)
      if (records[b])
        {
          body_outputs[b]->add_to_index(*records[b]);
          fields_complete_through = records[b]->first;
          completed               = true;
        }
    return completed;
  }



  // The bodies' .pvd (or .xdmf) and contact.pvd, the latter up to the
  // last cycle whose bodies' fields are complete.
  void
  TwoBodyProblem::write_field_indexes()
  {
    for (const auto &body_output : body_outputs)
      if (body_output)
        body_output->write_index(mpi_communicator);
    if (contact_output && fields_complete_through)
      contact_output->write_index(*fields_complete_through);
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
    const auto &a   = parameters.adaptation;
    last_adaptation = adapt_meshes({{bodies[0].get(), bodies[1].get()}},
                                   *error_estimate,
                                   previous_contact_states,
                                   a,
                                   parameters.finite_elements.degree,
                                   target_calibration.aim(a.target_error),
                                   target_calibration.model_checked());
    if (last_adaptation->predicted_epsilon > 0)
      target_calibration.record_plan(last_adaptation->predicted_epsilon);
    error_estimate.reset();
    cycle_report->record_mesh_adaptation(*last_adaptation,
                                         a,
                                         parameters.finite_elements.degree,
                                         target_calibration.correction());
  }



  bool
  TwoBodyProblem::continue_cycles(const unsigned int            cycle,
                                  const types::global_dof_index n_dofs,
                                  std::string                  &reason) const
  {
    const auto        &a = parameters.adaptation;
    std::ostringstream s;
    // An over-refined mesh is optimised again only while a further cycle
    // could still refine it should the coarser one miss the target.
    // It is not when the last remesh, planned coarser, gave each body the
    // cells it had: gmsh's coarsest mesh of the geometry, which another
    // plan would only solve again (epsilon_0 far above reach).
    const std::array<types::global_cell_index, 2> n_cells = {
      {bodies[0]->triangulation().n_global_active_cells(),
       bodies[1]->triangulation().n_global_active_cells()}};
    const bool at_coarsest_mesh =
      previous_cycle_n_cells && *previous_cycle_n_cells == n_cells;
    const bool over_refinement_possible =
      a.strategy == AdaptationStrategy::remesh && error_estimate &&
      error_estimate->epsilon < a.over_refinement_ratio * a.target_error &&
      cycle + 2 < a.n_cycles && n_dofs < a.max_dofs;
    // Nor when this mesh was planned at 'Minimum number of cells', or has
    // no more cells than that: a coarser plan would be raised to it, and
    // from a smaller mesh "optimising again" would refine.
    const bool at_minimum_cells =
      (last_adaptation && last_adaptation->limited_by_min_cells) ||
      n_cells[0] + n_cells[1] <= a.min_cells;
    const bool over_refined =
      over_refinement_possible && !at_coarsest_mesh && !at_minimum_cells;
    if (over_refined && error_estimate->epsilon <= a.target_error)
      pcout << "  over-refined: epsilon = " << std::setprecision(4)
            << 100 * error_estimate->epsilon << " % < "
            << a.over_refinement_ratio << " epsilon_0: optimising again"
            << std::endl;
    else if (over_refinement_possible && at_minimum_cells &&
             error_estimate->epsilon <= a.target_error)
      pcout << "  over-refined, but this mesh is at 'Adaptation/Minimum "
               "number of cells' = "
            << a.min_cells
            << " (planned at it, or smaller): not optimised again" << std::endl;
    else if (over_refinement_possible &&
             error_estimate->epsilon <= a.target_error)
      pcout << "  over-refined, but the last remesh kept every body's cell "
               "count ("
            << n_cells[0] << ", " << n_cells[1]
            << "): the coarsest mesh gmsh makes of the geometry; not "
               "optimised again"
            << std::endl;
    if (a.target_error > 0 && error_estimate &&
        error_estimate->epsilon <= a.target_error &&
        cycle + 1 >= a.min_cycles && !over_refined)
      {
        const TargetClaim claim = target_claim();
        s << "target reached: epsilon = " << std::setprecision(4)
          << 100 * error_estimate->epsilon
          << " % <= epsilon_0 = " << 100 * a.target_error << " %"
          << claim.qualifier(a.target_error);
        nlohmann::json entry = {{"estimate", claim.kind_of_estimate},
                                {"upper_bound", claim.is_upper_bound}};
        if (claim.epsilon_exact)
          entry["met_by_exact_error"] =
            claim.met_by_exact_error(a.target_error);
        cycle_report->set_run_entry("target_claim", entry);
      }
    else if (cycle + 1 >= a.n_cycles)
      {
        s << "maximum number of cycles (" << a.n_cycles << ") reached";
        if (a.target_error > 0 && error_estimate)
          s << " before the target: epsilon = " << std::setprecision(4)
            << 100 * error_estimate->epsilon
            << " % > epsilon_0 = " << 100 * a.target_error << " %";
      }
    else if (n_dofs >= a.max_dofs)
      s << "maximum number of DoFs reached (" << n_dofs << " >= " << a.max_dofs
        << ")";
    reason = s.str();
    return reason.empty();
  }



  // The bodies on the scene's meshes, their output writers and the
  // contact driver; before any solve, whether the exact error has
  // something to compare with.
  void
  TwoBodyProblem::make_bodies()
  {
    TimerOutput::Scope t(computing_timer, "setup");
    bodies = coulomb_adapt::make_bodies(mpi_communicator,
                                        *scene,
                                        parameters,
                                        parameters.mesh.global_refinements);
    for (unsigned int b = 0; b < 2; ++b)
      {
        body_outputs[b] =
          std::make_unique<BodyOutput>(parameters.output.directory,
                                       "body-" + std::to_string(b + 1),
                                       parameters.output.format,
                                       parameters.output.cells_per_vtu_piece);
      }
    contact_output =
      std::make_unique<ContactOutput>(parameters.output.directory,
                                      mpi_communicator,
                                      parameters.output.format);
    contact_solve_driver = std::make_unique<ContactSolveDriver>(
      mpi_communicator,
      *scene,
      std::array<ElasticBody *, 2>{{bodies[0].get(), bodies[1].get()}},
      parameters,
      pcout);
  }



  std::array<const ElasticBody *, 2>
  TwoBodyProblem::body_pointers() const
  {
    return coulomb_adapt::body_pointers(bodies);
  }



  // An error ends the run: summary.json says so, with the message the
  // user sees, before it propagates to main(), so that a script reading
  // the summaries of many runs finds the failed ones and why.
  void
  TwoBodyProblem::run()
  {
    try
      {
        run_cycles();
      }
    catch (const std::exception &e)
      {
        // summary.json first: it is written without communication, in
        // case another rank is failing elsewhere.
        const std::string not_written =
          cycle_report->record_failure(current_cycle, user_message(e));
        if (!not_written.empty())
          pcout << "  summary.json not updated with the error: " << not_written
                << std::endl;
        // The finished cycles' fields stay: the one still being written
        // in the background is completed and indexed. Collective: the
        // program's errors reach every rank (an error on one rank alone
        // would leave the others waiting in any case).
        try
          {
            if (complete_background_writes())
              write_field_indexes();
          }
        catch (const std::exception &output_error)
          {
            pcout << "  the fields of the cycle before were not completed: "
                  << user_message(output_error) << std::endl;
          }
        throw;
      }
  }



  void
  TwoBodyProblem::run_cycles()
  {
    pcout << "coulomb-adapt: scene '" << scene->name() << "', "
          << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " MPI rank(s), " << MultithreadInfo::n_threads()
          << " thread(s) per rank, results in '" << parameters.output.directory
          << "'" << std::endl;
    remove_output_of_earlier_run(mpi_communicator,
                                 parameters.output.directory,
                                 pcout);
    make_bodies();
    if (parameters.output.format == OutputFormat::hdf5 &&
        parameters.output.write_cycles != WriteCycles::none &&
        patch_subdivisions(bodies[0]->triangulation(),
                           parameters.finite_elements.degree,
                           OutputFormat::hdf5) <
          parameters.finite_elements.degree)
      pcout << "  output: HDF5 holds the P" << parameters.finite_elements.degree
            << " triangles' fields at their vertices only (deal.II 9.4's "
               "HDF5 writer has no curved or quadratic triangles); "
               "'Output/Format = vtu' writes the quadratic cells"
            << std::endl;
    if (parameters.error_indicator.estimator != ErrorEstimator::cre &&
        parameters.output.write_cycles != WriteCycles::none &&
        !parameters.output.write_smoothed_stress)
      pcout << "  output: the estimator's smoothed stress is not written "
               "('Output/Write smoothed stress = true' adds it)"
            << std::endl;
    if (parameters.error_indicator.estimator == ErrorEstimator::zz &&
        parameters.finite_elements.degree >= 2)
      pcout << "  warning: "
            << zz_degree_warning(parameters.finite_elements.degree)
            << std::endl;
    const LoadStressScale loads = load_stress_scale(*scene, bodies);
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
        current_cycle = cycle;
        cycle_report->begin_cycle(cycle);
        if (cycle > 0)
          refine_grid();
        setup_system();
        if (cycle == 0)
          choose_load_scale(loads);
        cycle_report->record_meshes(body_pointers(),
                                    parameters.adaptation.strategy,
                                    last_adaptation ? &*last_adaptation :
                                                      nullptr,
                                    target_calibration.correction());
        if (scene->n_load_steps() > 1)
          scene->set_load_step(1);
        assemble_system();
        solve();
        estimate_error();
        target_calibration.record_achieved(error_estimate->epsilon);
        const std::array<double, 2> strain_energies = record_strain_energies();
        // Timed on its own: a verification cost, not the indicator's.
        if (parameters.error_indicator.compute_exact_error)
          {
            compare_with_exact_error(strain_energies);
            // A verification run checks the bound it claims, every cycle.
            if (target_claim().is_upper_bound)
              cycle_report->record_claimed_bound(error_estimate->epsilon);
          }
        compare_with_exact_displacements();
        // Decided before the output: 'Write cycles = last' writes the
        // fields of the cycle after which the adaptation stops.
        std::string reason;
        const bool  last_cycle =
          !continue_cycles(cycle, cycle_report->n_dofs(), reason);
        output_results(cycle, last_cycle);
        cycle_report->end_cycle(*error_estimate, contact_solver != nullptr);
        previous_cycle_n_cells = std::array<types::global_cell_index, 2>{
          {bodies[0]->triangulation().n_global_active_cells(),
           bodies[1]->triangulation().n_global_active_cells()}};
        if (last_cycle)
          {
            cycle_report->record_stop(cycle, reason);
            break;
          }
      }
    cycle_report->print_table();
    computing_timer.print_summary();
    pcout << "(the 'error indicator: ...' sections are parts of 'error "
             "indicator': the percentages add up to more than 100)"
          << std::endl;
  }
} // namespace coulomb_adapt
