#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/nested_iteration.h>

#include <algorithm>
#include <iostream>
#include <memory>

namespace coulomb_adapt
{
  namespace
  {
    // Solve the contact problem on @p bodies (set up and assembled here),
    // warm-started from @p states when there are any; @p states receives
    // the solution's sets and @p level what the solve did.
    //
    // A level whose solve stops with a diagnosis is left out (false, no
    // record): the coarsest meshes are the least reliable (dovetail's
    // .geo at 8x its mesh size: "would slide" in its second step), and the
    // next finer level starts from the initial gap instead.
    bool
    solve_level(const ElasticBodies            &bodies,
                const parameters::Contact      &contact_parameters,
                const parameters::LinearSolver &solver_parameters,
                std::vector<ContactNodeState>  &states,
                NestedIterationLevel           &level)
    {
      // The coarse solves' Newton lines would drown the fine one's: each
      // level is reported by the caller in one line instead.
      const ConditionalOStream silent(std::cout, false);
      Timer                    timer;
      for (auto &body : bodies)
        {
          body->setup_system();
          body->assemble_system();
        }
      ContactSolver solver(
        *bodies[0], *bodies[1], contact_parameters, solver_parameters, silent);
      if (!states.empty())
        solver.warm_start_from(states);
      ContactSolverReport report;
      try
        {
          report = solver.solve();
        }
      catch (const ContactDiagnosis &)
        {
          states.clear();
          return false;
        }
      states = solver.node_states();
      timer.stop();
      level.n_dofs =
        bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
      level.newton_iterations = report.newton_iterations;
      level.n_active          = report.n_active;
      level.wall_time         = timer.wall_time();
      return true;
    }



    // Load step @p step of a coarser level's path: started from the same
    // step's sets on the next coarser level (@p coarser_path), if any, or
    // predicted from the level's previous step; its sets appended to
    // @p level_path. False if the solve stopped with a diagnosis (the
    // level is then left out, and the next finer one solves its path from
    // its own steps, as for a static level).
    bool
    solve_level_load_step(
      const Scene                                      &level_scene,
      const ElasticBodies                              &bodies,
      ContactSolver                                    &solver,
      const unsigned int                                step,
      const std::vector<std::vector<ContactNodeState>> &coarser_path,
      const parameters::Contact                        &contact_parameters,
      NestedIterationLevel                             &level,
      std::vector<std::vector<ContactNodeState>>       &level_path)
    {
      level_scene.set_load_step(step);
      for (auto &body : bodies)
        {
          body->setup_system();
          body->assemble_system();
        }
      if (!coarser_path.empty())
        solver.warm_start_from(coarser_path[step - 1]);
      else if (step > 1 && contact_parameters.load_step_predictor &&
               level_scene.load_increment_ratio(step) > 0)
        solver.predict_next_load_step(level_scene.load_increment_ratio(step));
      ContactSolverReport report;
      try
        {
          report = solver.solve();
        }
      catch (const ContactDiagnosis &)
        {
          return false;
        }
      level_path.push_back(solver.node_states());
      level.newton_iterations_per_load_step.push_back(report.newton_iterations);
      level.newton_iterations =
        std::max(level.newton_iterations, report.newton_iterations);
      level.n_active = report.n_active;
      return true;
    }
  } // namespace



  std::vector<ContactNodeState>
  predict_contact_sets_on_coarser_meshes(
    const MPI_Comm                     mpi_communicator,
    const Scene                       &scene,
    const CellType                     cell_type,
    const unsigned int                 fine_refinements,
    const unsigned int                 n_levels,
    const parameters::FiniteElements  &fe_parameters,
    const parameters::Contact         &contact_parameters,
    const parameters::LinearSolver    &solver_parameters,
    std::vector<NestedIterationLevel> &levels)
  {
    Assert(n_levels <= fine_refinements, ExcInternalError());
    levels.clear();
    const unsigned int coarsest = fine_refinements - n_levels;

    // The scene's own meshes (no refinement) of a scene that grades them
    // (hertz, cattaneo) have many nodes across the contact zone: started
    // from the initial gap they take 7-8 Newton steps themselves (hertz
    // Q1, 9,198 DoFs: 8). They start from their coarser gradings instead,
    // as a fine mesh without refinements does.
    std::vector<ContactNodeState> states;
    if (coarsest == 0 && contact_parameters.nested_iteration_levels > 0 &&
        scene.with_coarser_graded_meshes(1) != nullptr)
      states = predict_contact_sets_on_coarser_graded_meshes(
        mpi_communicator,
        scene,
        cell_type,
        contact_parameters.nested_iteration_levels,
        fe_parameters,
        contact_parameters,
        solver_parameters,
        levels);

    const ElasticBodies bodies =
      make_bodies(mpi_communicator, scene, cell_type, coarsest, fe_parameters);
    for (unsigned int r = coarsest; r < fine_refinements; ++r)
      {
        if (r > coarsest)
          for (auto &body : bodies)
            body->refine_uniformly();
        NestedIterationLevel level;
        level.global_refinements = r;
        if (solve_level(
              bodies, contact_parameters, solver_parameters, states, level))
          levels.push_back(level);
      }
    return states;
  }



  std::vector<ContactNodeState>
  predict_contact_sets_on_coarser_graded_meshes(
    const MPI_Comm                     mpi_communicator,
    const Scene                       &scene,
    const CellType                     cell_type,
    const unsigned int                 n_levels,
    const parameters::FiniteElements  &fe_parameters,
    const parameters::Contact         &contact_parameters,
    const parameters::LinearSolver    &solver_parameters,
    std::vector<NestedIterationLevel> &levels)
  {
    levels.clear();
    std::vector<ContactNodeState> states;
    for (unsigned int k = n_levels; k >= 1; --k)
      {
        // A grading the scene cannot mesh is left out, as a level that
        // stops is.
        const std::unique_ptr<Scene> coarser =
          scene.with_coarser_graded_meshes(k);
        if (!coarser)
          {
            states.clear();
            continue;
          }
        const ElasticBodies bodies =
          make_bodies(mpi_communicator, *coarser, cell_type, 0, fe_parameters);
        NestedIterationLevel level;
        level.coarsening = k;
        if (solve_level(
              bodies, contact_parameters, solver_parameters, states, level))
          levels.push_back(level);
      }
    return states;
  }



  namespace
  {
    // One coarser mesh of a load path's nested iteration: the scene's
    // meshes (or a coarser grading of them) with some global refinements.
    struct CoarserMeshes
    {
      std::unique_ptr<Scene> coarser_scene; // a coarser grading, or null
      unsigned int           global_refinements = 0;
      unsigned int           coarsening         = 0;
    };

    // The coarser meshes, coarsest first, as the static nested iteration
    // takes them.
    std::vector<CoarserMeshes>
    coarser_meshes(const Scene       &scene,
                   const unsigned int fine_refinements,
                   const unsigned int n_levels,
                   const bool         graded,
                   const unsigned int n_graded_levels)
    {
      std::vector<CoarserMeshes> meshes;
      const unsigned int         coarsest =
        graded ? 0 : fine_refinements - std::min(n_levels, fine_refinements);
      const unsigned int n_gradings =
        graded ? n_levels :
        (coarsest == 0 && scene.with_coarser_graded_meshes(1) != nullptr) ?
                 n_graded_levels :
                 0;
      for (unsigned int k = n_gradings; k >= 1; --k)
        {
          CoarserMeshes m;
          m.coarser_scene = scene.with_coarser_graded_meshes(k);
          m.coarsening    = k;
          if (m.coarser_scene)
            meshes.push_back(std::move(m));
        }
      if (!graded)
        for (unsigned int r = coarsest; r < fine_refinements; ++r)
          {
            CoarserMeshes m;
            m.global_refinements = r;
            meshes.push_back(std::move(m));
          }
      return meshes;
    }
  } // namespace



  std::vector<std::vector<ContactNodeState>>
  predict_load_path_on_coarser_meshes(
    const MPI_Comm                     mpi_communicator,
    const Scene                       &scene,
    const CellType                     cell_type,
    const unsigned int                 fine_refinements,
    const unsigned int                 n_levels,
    const bool                         graded,
    const parameters::FiniteElements  &fe_parameters,
    const parameters::Contact         &contact_parameters,
    const parameters::LinearSolver    &solver_parameters,
    std::vector<NestedIterationLevel> &levels)
  {
    levels.clear();
    const ConditionalOStream   silent(std::cout, false);
    const unsigned int         n_steps = scene.n_load_steps();
    std::vector<CoarserMeshes> meshes =
      coarser_meshes(scene,
                     fine_refinements,
                     n_levels,
                     graded,
                     contact_parameters.nested_iteration_levels);
    std::vector<std::vector<ContactNodeState>> path;
    for (const CoarserMeshes &m : meshes)
      {
        const Scene &level_scene = m.coarser_scene ? *m.coarser_scene : scene;
        Timer        timer;
        const ElasticBodies  bodies = make_bodies(mpi_communicator,
                                                 level_scene,
                                                 cell_type,
                                                 m.global_refinements,
                                                 fe_parameters);
        ContactSolver        solver(*bodies[0],
                             *bodies[1],
                             contact_parameters,
                             solver_parameters,
                             silent);
        NestedIterationLevel level;
        level.global_refinements = m.global_refinements;
        level.coarsening         = m.coarsening;
        std::vector<std::vector<ContactNodeState>> level_path;
        bool                                       stopped = false;
        for (unsigned int step = 1; step <= n_steps && !stopped; ++step)
          stopped = !solve_level_load_step(level_scene,
                                           bodies,
                                           solver,
                                           step,
                                           path,
                                           contact_parameters,
                                           level,
                                           level_path);
        if (stopped)
          {
            path.clear();
            continue;
          }
        timer.stop();
        level.n_dofs =
          bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
        level.wall_time = timer.wall_time();
        levels.push_back(level);
        path = std::move(level_path);
      }
    return path;
  }
} // namespace coulomb_adapt
