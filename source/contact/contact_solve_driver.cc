#include <deal.II/base/patterns.h>

#include <deal.II/distributed/tria.h>

#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_linear_solver_choice.h>
#include <coulomb_adapt/contact/contact_solve_driver.h>
#include <coulomb_adapt/core/parameter_error.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

namespace coulomb_adapt
{
  namespace
  {
    // Why the nested iteration does not run on @p n_levels coarser
    // meshes (@p graded: the scene's coarser gradings, else fewer global
    // refinements) for @p n_dofs fine DoFs; empty if it runs.
    std::string
    nested_iteration_skipped(const parameters::Contact    &c,
                             const types::global_dof_index n_dofs,
                             const bool                    graded,
                             const unsigned int            n_levels)
    {
      if (c.nested_iteration_levels == 0)
        return "switched off ('Contact/Nested iteration levels' = 0)";
      if (n_levels == 0)
        return "no coarser mesh ('Mesh/Global refinements' = 0, and the "
               "scene neither grades its meshes nor meshes a .geo file)";
      // A graded mesh resolves the contact zone much finer than the
      // bodies: many nodes across the zone, which the cold start's Newton
      // iteration releases a band at a time, so its step count grows with
      // them at every size. The DoF threshold is for global refinements
      // only.
      if (!graded && n_dofs <= c.nested_iteration_min_dofs)
        return std::to_string(n_dofs) +
               " DoFs <= 'Contact/Nested iteration minimum DoFs' (" +
               std::to_string(c.nested_iteration_min_dofs) + ")";
      return "";
    }



    // The sets that start the fine solve, from the coarser meshes: for a
    // load path (scene.n_load_steps() > 1) the whole path is solved there
    // and @p load_path receives each step's sets (the first step's are
    // returned); otherwise the coarser global refinements, or with
    // @p graded the scene's coarser gradings.
    std::vector<ContactNodeState>
    predict_on_coarser_meshes(
      const MPI_Comm                              mpi_communicator,
      const Scene                                &scene,
      const Parameters                           &parameters,
      const unsigned int                          n_levels,
      const bool                                  graded,
      std::vector<std::vector<ContactNodeState>> &load_path,
      std::vector<NestedIterationLevel>          &levels)
    {
      if (scene.n_load_steps() > 1)
        {
          load_path = predict_load_path_on_coarser_meshes(
            mpi_communicator,
            scene,
            parameters.mesh.cell_type,
            parameters.mesh.global_refinements,
            n_levels,
            graded,
            parameters.finite_elements,
            parameters.contact,
            parameters.linear_solver,
            levels);
          return load_path.empty() ? std::vector<ContactNodeState>() :
                                     load_path.front();
        }
      if (graded)
        return predict_contact_sets_on_coarser_graded_meshes(
          mpi_communicator,
          scene,
          parameters.mesh.cell_type,
          n_levels,
          parameters.finite_elements,
          parameters.contact,
          parameters.linear_solver,
          levels);
      return predict_contact_sets_on_coarser_meshes(
        mpi_communicator,
        scene,
        parameters.mesh.cell_type,
        parameters.mesh.global_refinements,
        n_levels,
        parameters.finite_elements,
        parameters.contact,
        parameters.linear_solver,
        levels);
    }



    // One line per coarser level the nested iteration solved.
    void
    log_nested_iteration_levels(const ConditionalOStream                &pcout,
                                const std::vector<NestedIterationLevel> &levels)
    {
      for (const NestedIterationLevel &l : levels)
        {
          pcout << "  contact: nested iteration, "
                << (l.from_own_hierarchy ?
                      "cells up to level " +
                        std::to_string(l.finest_cell_level) :
                    l.coarsening > 0 ?
                      (l.every_size_scaled ? "mesh sizes " : "graded zone ") +
                        std::to_string(1u << l.coarsening) + "x coarser" :
                      std::to_string(l.global_refinements) +
                        " global refinements")
                << ": " << l.n_dofs << " DoFs, ";
          if (l.newton_iterations_per_load_step.empty())
            pcout << l.newton_iterations;
          else
            for (unsigned int i = 0;
                 i < l.newton_iterations_per_load_step.size();
                 ++i)
              pcout << (i > 0 ? " " : "")
                    << l.newton_iterations_per_load_step[i];
          pcout << " Newton steps"
                << (l.newton_iterations_per_load_step.empty() ?
                      "" :
                      " (per load step)")
                << ", " << l.n_active << " active nodes, "
                << std::setprecision(3) << l.wall_time << " s" << std::endl;
        }
    }


    // Runs @p predict, the solves on coarser meshes of @p start ("nested
    // iteration", "nested start"), and logs their levels. A coarser
    // solve that throws abandons the start (a coarse mesh that does not
    // converge says nothing about the fine one): false, the log names
    // what failed and what the fine solve starts from instead
    // (@p instead, may be empty), and @p record why.
    bool
    solve_on_coarser_meshes(
      const ConditionalOStream                             &pcout,
      const std::string                                    &start,
      const std::string                                    &instead,
      const std::function<std::vector<ContactNodeState>()> &predict,
      std::vector<ContactNodeState>                        &predicted_sets,
      NestedIterationRecord                                &record)
    {
      try
        {
          predicted_sets = predict();
        }
      catch (const std::exception &e)
        {
          const std::string what = user_message(e);
          pcout << "  contact: " << start
                << " abandoned, a coarser solve failed: " << what << instead
                << std::endl;
          record.levels.clear();
          record.skipped = "a coarser solve failed: " + what;
          return false;
        }
      log_nested_iteration_levels(pcout, record.levels);
      return true;
    }



    // A cycle's nested start: says why (@p why) and from which coarser
    // meshes (@p meshes), then solves them (@p predict) as
    // solve_on_coarser_meshes() does. False, with the reason in
    // @p record, when it gives no sets: the cycle keeps the warm start.
    bool
    nested_start(const ConditionalOStream                             &pcout,
                 const std::string                                    &why,
                 const std::string                                    &meshes,
                 const std::function<std::vector<ContactNodeState>()> &predict,
                 std::vector<ContactNodeState> &predicted_sets,
                 NestedIterationRecord         &record)
    {
      pcout << "  contact: nested start (" << why << "): " << meshes
            << ", instead of the previous cycle's sets" << std::endl;
      if (!solve_on_coarser_meshes(pcout,
                                   "nested start",
                                   "; the previous cycle's sets instead",
                                   predict,
                                   predicted_sets,
                                   record))
        return false;
      if (predicted_sets.empty())
        record.skipped = "every coarser solve stopped with a diagnosis";
      return !predicted_sets.empty();
    }
  } // namespace



  ContactSolveDriver::ContactSolveDriver(
    const MPI_Comm                      mpi_communicator,
    const Scene                        &scene,
    const std::array<ElasticBody *, 2> &bodies,
    const Parameters                   &parameters,
    const ConditionalOStream           &pcout)
    : mpi_communicator(mpi_communicator)
    , scene(scene)
    , bodies(bodies)
    , parameters(parameters)
    , pcout(pcout)
  {}



  // The start: the previous cycle's sets (warm start), else on the first
  // meshes the sets of the coarser meshes (nested iteration), else the
  // initial gap. On a load path (quasi-static scene) the start is that of
  // its first load step only: the later steps go on from the step before,
  // whose stick/slip history lives in the solver, and the first step's
  // start is a guess like any other (the Newton iteration runs to its own
  // convergence), so a load path starts as a static problem does.
  ContactSolveOutcome
  ContactSolveDriver::solve(
    const std::vector<ContactNodeState> &previous_states,
    const bool                           first_meshes)
  {
    pcout << "  contact: "
          << (parameters.contact.friction_coefficient > 0 ?
                "Coulomb friction, mu = " +
                  Patterns::Tools::Convert<double>::to_string(
                    parameters.contact.friction_coefficient) :
                std::string("frictionless (mu = 0): no "
                            "stick/slip sets"))
          << std::endl;
    ContactSolveOutcome                  outcome;
    const std::vector<ContactNodeState> &previous_start =
      scene.n_load_steps() == 1 ? previous_states : first_load_step_states;
    outcome.warm_start = parameters.adaptation.warm_start &&
                         !previous_states.empty() && !previous_start.empty();
    const types::global_dof_index n_dofs =
      bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
    if (first_meshes)
      first_meshes_dofs = n_dofs;
    std::vector<ContactNodeState> predicted_sets;
    if (outcome.warm_start)
      predicted_sets = previous_start;
    bool nested = false;
    coarser_load_path.clear();
    if (!outcome.warm_start && first_meshes)
      {
        outcome.nested_iteration.emplace();
        nested =
          start_from_coarser_meshes(predicted_sets, *outcome.nested_iteration);
      }
    else if (outcome.warm_start && after_large_refinement(n_dofs))
      {
        outcome.nested_iteration.emplace();
        std::vector<ContactNodeState> uniform_sets;
        nested = start_from_own_hierarchy() ?
                   start_from_coarser_hierarchy(n_dofs,
                                                uniform_sets,
                                                *outcome.nested_iteration) :
                   start_from_uniform_refinements(n_dofs,
                                                  uniform_sets,
                                                  *outcome.nested_iteration);
        if (nested)
          {
            outcome.warm_start = false;
            predicted_sets     = std::move(uniform_sets);
          }
      }
    last_n_dofs                = n_dofs;
    const bool predicted_start = outcome.warm_start || nested;
    outcome.solver             = new_solver(parameters.contact,
                                predicted_start ? &predicted_sets : nullptr);
    pcout << "  contact: Newton starts from "
          << (outcome.warm_start ?
                "the previous cycle's contact sets (warm start)" :
              nested ? "the sets of the coarser meshes (nested iteration)" :
                       "the initial gap")
          << std::endl;
    pcout << "  contact: linear solver "
          << choose_contact_linear_solver(parameters.linear_solver,
                                          bodies[0]->dof_handler().n_dofs() +
                                            bodies[1]->dof_handler().n_dofs(),
                                          *krylov_failures)
               .description
          << std::endl;

    solve_load_steps(restarts(predicted_start), predicted_sets, outcome);
    measure_initial_gap(outcome);
    outcome.linear_solver  = outcome.solver->last_linear_solver_report();
    outcome.krylov_failure = krylov_failures->failure;
    return outcome;
  }



  std::unique_ptr<ContactSolver>
  ContactSolveDriver::new_solver(
    const parameters::Contact           &c,
    const std::vector<ContactNodeState> *predicted_sets) const
  {
    auto solver = std::make_unique<ContactSolver>(*bodies[0],
                                                  *bodies[1],
                                                  c,
                                                  parameters.linear_solver,
                                                  pcout,
                                                  krylov_failures);
    if (predicted_sets != nullptr)
      solver->warm_start_from(*predicted_sets);
    return solver;
  }



  // Where a static solve goes on when it stops with a diagnosis (a
  // ContactDiagnosis; other errors end the run). Sets predicted on another
  // mesh (warm start, nested iteration) can start the iteration on the
  // wrong side of a diagnosis (an all-slip first step), which is not the
  // problem's failure: first the initial gap. Then, if the user scaled
  // c_n = c_t, the natural constants, from the predicted sets and from the
  // initial gap: the solution does not depend on c, only the path of the
  // active set iteration does, and an extreme scale can keep the sets from
  // settling. A quasi-static path is restarted only in its first load
  // step, and only from the initial gap: later, its stick/slip history
  // lives in the solver.
  std::vector<ContactSolveDriver::Restart>
  ContactSolveDriver::restarts(const bool predicted_start) const
  {
    std::vector<Restart> restarts;
    if (predicted_start)
      restarts.push_back({parameters.contact,
                          false,
                          "from the initial gap",
                          "retried_from_initial_gap"});
    if (scene.n_load_steps() != 1)
      return restarts;
    if (parameters.contact.complementarity_scale != 1.)
      {
        parameters::Contact natural   = parameters.contact;
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
    return restarts;
  }



  // Nested iteration (contact/nested_iteration.h) on the first cycle: the
  // bodies are still the scene's meshes with 'Global refinements', so the
  // coarser ones are the same meshes with fewer, or, without any, the
  // scene's coarser gradings. Whether it runs, and why not, goes to the log
  // and the record.
  bool
  ContactSolveDriver::start_from_coarser_meshes(
    std::vector<ContactNodeState> &predicted_sets,
    NestedIterationRecord         &record)
  {
    const auto                   &c = parameters.contact;
    const types::global_dof_index n_dofs =
      bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
    // Without global refinements, a scene that grades its meshes (hertz)
    // or meshes a .geo file offers coarser meshes of the same geometry
    // instead (asked for only if nested iteration is on: a .geo file is
    // meshed to answer).
    const bool graded = c.nested_iteration_levels > 0 &&
                        parameters.mesh.global_refinements == 0 &&
                        scene.with_coarser_graded_meshes(1) != nullptr;
    const unsigned int n_levels =
      graded ?
        c.nested_iteration_levels :
        std::min(c.nested_iteration_levels, parameters.mesh.global_refinements);
    record.skipped = nested_iteration_skipped(c, n_dofs, graded, n_levels);
    if (!record.skipped.empty())
      {
        pcout << "  contact: nested iteration skipped: " << record.skipped
              << std::endl;
        return false;
      }

    // Abandoned, the fine solve starts cold and decides for itself.
    if (!solve_on_coarser_meshes(
          pcout,
          "nested iteration",
          "",
          [&] {
            return predict_on_coarser_meshes(mpi_communicator,
                                             scene,
                                             parameters,
                                             n_levels,
                                             graded,
                                             coarser_load_path,
                                             record.levels);
          },
          predicted_sets,
          record))
      {
        coarser_load_path.clear();
        return false;
      }
    return !predicted_sets.empty() || !record.levels.empty();
  }



  // After a large refinement (a first adaptation step from a coarse
  // initial mesh: blocks, refine, 144 -> 23,600 DoFs) the previous cycle
  // had a few contact nodes (4) where the new meshes have many (75), and
  // the sets carried over by position put the stick/slip front where the
  // coarse solution had it, up to half a coarse element off. The Newton
  // iteration then moves the front about one node per step and side, and
  // a start with too much slip can run away towards sliding before it
  // comes back (that run: 22 steps; its cold start: 6). Uniform refinements
  // of the scene's meshes resolve the contact zone about as the new meshes
  // do at a fraction of their DoFs, and their nested iteration places the
  // front to within their node spacing. Static scenes only: a load path's
  // warm start carries its first load step's sets, not a static problem's.
  bool
  ContactSolveDriver::after_large_refinement(
    const types::global_dof_index n_dofs) const
  {
    const double ratio = parameters.adaptation.nested_start_dof_ratio;
    return ratio > 0 && scene.n_load_steps() == 1 && last_n_dofs > 0 &&
           first_meshes_dofs > 0 &&
           parameters.contact.nested_iteration_levels > 0 &&
           n_dofs > parameters.contact.nested_iteration_min_dofs &&
           static_cast<double>(n_dofs) >=
             ratio * static_cast<double>(last_n_dofs);
  }



  // The finest R with the scene's meshes refined R times at most the
  // cycle's DoFs (estimated as 4^(R - g) times those of the first meshes,
  // g = 'Mesh/Global refinements'; an over-estimate for linear elements),
  // and the levels below it as the first cycle's nested iteration takes
  // them. Up to the cycle's own size, not less: an adapted mesh resolves
  // the contact zone much finer than a uniform one of its DoFs (blocks'
  // default mesh, remesh to 0.5 %: from the uniform level of 10,628 DoFs
  // the 50,750-DoF cycle took 5 Newton steps, from that of 41,732 one).
  // A coarser solve that fails leaves the warm start.
  bool
  ContactSolveDriver::start_from_uniform_refinements(
    const types::global_dof_index  n_dofs,
    std::vector<ContactNodeState> &predicted_sets,
    NestedIterationRecord         &record)
  {
    const unsigned int g = parameters.mesh.global_refinements;
    int                R = -static_cast<int>(g);
    while (static_cast<double>(first_meshes_dofs) * std::pow(4., R + 1) <=
           static_cast<double>(n_dofs))
      ++R;
    const int finest = static_cast<int>(g) + R;
    if (finest < 1)
      {
        record.skipped = "no uniform refinement of the scene's meshes has "
                         "at most the cycle's DoFs";
        pcout << "  contact: nested start skipped ("
              << nested_start_reason(n_dofs) << "): " << record.skipped
              << std::endl;
        return false;
      }
    const auto        &c = parameters.contact;
    const unsigned int n_levels =
      std::min<unsigned int>(c.nested_iteration_levels + 1,
                             static_cast<unsigned int>(finest) + 1);
    return nested_start(
      pcout,
      nested_start_reason(n_dofs),
      "the scene's meshes refined up to " + std::to_string(finest) + " times",
      [&] {
        return predict_contact_sets_on_coarser_meshes(
          mpi_communicator,
          scene,
          parameters.mesh.cell_type,
          finest + 1,
          n_levels,
          parameters.finite_elements,
          c,
          parameters.linear_solver,
          record.levels);
      },
      predicted_sets,
      record);
  }



  // The cycle's own hierarchy (predict_contact_sets_on_coarser_hierarchy()
  // chooses its levels), as many as the uniform start takes at most.
  bool
  ContactSolveDriver::start_from_coarser_hierarchy(
    const types::global_dof_index  n_dofs,
    std::vector<ContactNodeState> &predicted_sets,
    NestedIterationRecord         &record)
  {
    const auto &c = parameters.contact;
    return nested_start(
      pcout,
      nested_start_reason(n_dofs),
      "the cycle's meshes with their finest cell levels coarsened",
      [&] {
        return predict_contact_sets_on_coarser_hierarchy(
          mpi_communicator,
          scene,
          parameters.mesh.cell_type,
          {{bodies[0], bodies[1]}},
          c.nested_iteration_levels + 1,
          parameters.finite_elements,
          c,
          parameters.linear_solver,
          record.levels);
      },
      predicted_sets,
      record);
  }



  std::string
  ContactSolveDriver::nested_start_reason(
    const types::global_dof_index n_dofs) const
  {
    std::ostringstream why;
    why << "the cycle's " << n_dofs << " DoFs are at least "
        << parameters.adaptation.nested_start_dof_ratio
        << " times the previous cycle's " << last_n_dofs;
    return why.str();
  }



  // Whether the nested start takes the cycle's own hierarchy: both
  // bodies' meshes are refined in place (p4est, quadrilaterals; a remeshed
  // or triangle mesh has no hierarchy), and the scene does not grade its
  // meshes towards the contact zone. A graded scene's uniform refinements
  // resolve the zone as finely as the adapted cycle, its own hierarchy's
  // levels with at most 2/3 of the cells do not (hertz Q1 refine,
  // epsilon_0 = 0.25 %, 322,988 DoFs, 313 active nodes: from the uniform
  // level of 140,316 DoFs 3 Newton steps; from the hierarchy's level of
  // 141,020 DoFs, 71 active nodes, 6, and then the residual stayed above
  // the tolerance).
  bool
  ContactSolveDriver::start_from_own_hierarchy() const
  {
    for (const ElasticBody *body : bodies)
      if (dynamic_cast<const parallel::distributed::Triangulation<2> *>(
            &body->triangulation()) == nullptr)
        return false;
    // Asked last: a scene that meshes a .geo file meshes it to answer.
    return scene.with_coarser_graded_meshes(1) == nullptr;
  }



  // The scene's load path: one step for the static problem, several for a
  // quasi-static one (the solver keeps the stick/slip history). A start
  // that stops with a diagnosis is followed by the next restart; the last
  // one's diagnosis ends the run.
  void
  ContactSolveDriver::solve_load_steps(
    const std::vector<Restart>          &restarts,
    const std::vector<ContactNodeState> &predicted_sets,
    ContactSolveOutcome                 &outcome)
  {
    const unsigned int n_steps                 = scene.n_load_steps();
    unsigned int       total_newton_iterations = 0;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        if (n_steps > 1)
          {
            pcout << "  load step " << step << "/" << n_steps << std::endl;
            scene.set_load_step(step);
            // Dirichlet data may follow the load path: new constraints.
            for (ElasticBody *body : bodies)
              {
                body->setup_system();
                body->assemble_system();
              }
            // Nested iteration along the path: the same load step's sets
            // on the finest coarser mesh; else the load-step predictor.
            if (coarser_load_path.size() == n_steps)
              outcome.solver->warm_start_from(coarser_load_path[step - 1]);
            else if (parameters.contact.load_step_predictor &&
                     scene.load_increment_ratio(step) > 0)
              outcome.solver->predict_next_load_step(
                scene.load_increment_ratio(step));
          }
        for (unsigned int attempt = 0;; ++attempt)
          try
            {
              outcome.report = outcome.solver->solve();
              break;
            }
          catch (const ContactDiagnosis &e)
            {
              outcome.newton_iterations_of_stopped_starts += e.newton_steps;
              if (attempt == restarts.size() || step > 1)
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
              outcome.restarts.push_back(restart.summary_key);
              outcome.solver =
                new_solver(restart.contact,
                           restart.from_predicted_sets ? &predicted_sets :
                                                         nullptr);
            }
        outcome.newton_iterations_of_stopped_starts +=
          outcome.report.newton_iterations_of_stopped_prediction;
        total_newton_iterations += outcome.report.newton_iterations;
        outcome.newton_iterations_per_load_step.push_back(
          outcome.report.newton_iterations);
        outcome.contact_moment_per_load_step.push_back(
          outcome.report.contact_moment);
        if (step == 1 && n_steps > 1)
          first_load_step_states = outcome.solver->node_states();
      }
    outcome.report.newton_iterations = total_newton_iterations;
    outcome.n_load_steps             = n_steps;
  }



  // The initial gap where the bodies face each other: an interference
  // (press) fit starts with an overlap (negative gap), a clearance fit with
  // a positive one. (The solver builds the mortar interface when it
  // solves.)
  void
  ContactSolveDriver::measure_initial_gap(ContactSolveOutcome &outcome) const
  {
    const MortarInterface &mortar = outcome.solver->mortar_interface();
    for (unsigned int j = 0; j < mortar.slave_nodes().size(); ++j)
      if (mortar.is_covered(j))
        {
          const double g =
            mortar.weighted_initial_gaps()[j] / mortar.slave_weights()[j];
          outcome.initial_overlap   = std::max(outcome.initial_overlap, -g);
          outcome.initial_clearance = std::max(outcome.initial_clearance, g);
        }
  }
} // namespace coulomb_adapt
