#include <deal.II/base/array_view.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/nested_iteration.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <set>

namespace coulomb_adapt
{
  namespace
  {
    // Solve the contact problem on @p bodies (set up and assembled here),
    // warm-started from @p states when there are any; @p states receives
    // the solution's sets, and @p levels gets @p level (which meshes) with
    // what the solve did.
    //
    // A level whose solve stops with a diagnosis is left out (no record):
    // the coarsest meshes are the least reliable (dovetail's
    // .geo at 8x its mesh size: "would slide" in its second step), and the
    // next finer level starts from the initial gap instead.
    void
    solve_level(const ElasticBodies               &bodies,
                const parameters::Contact         &contact_parameters,
                const parameters::LinearSolver    &solver_parameters,
                std::vector<ContactNodeState>     &states,
                NestedIterationLevel               level,
                std::vector<NestedIterationLevel> &levels)
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
          return;
        }
      states = solver.node_states();
      timer.stop();
      level.n_dofs =
        bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
      level.newton_iterations = report.newton_iterations;
      level.n_active          = report.n_active;
      level.wall_time         = timer.wall_time();
      levels.push_back(level);
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



    // The cells of both bodies' meshes with every cell beyond level L
    // coarsened, L = 0 ... @p finest, counted from the active cells per
    // level: from the finest level down, each refined cell has
    // max_children_per_cell (4) children, so the cells of level L are the
    // active ones plus a quarter of those of level L + 1; the mesh cut at
    // L has those and every active cell below L.
    std::vector<double>
    cells_up_to_level(const std::array<const ElasticBody *, 2> &bodies,
                      const unsigned int                        finest)
    {
      std::vector<double> cells(finest + 1, 0.);
      for (const ElasticBody *body : bodies)
        {
          std::vector<double> active(finest + 1, 0.);
          for (const auto &cell : body->triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              active[cell->level()] += 1;
          Utilities::MPI::sum(ArrayView<const double>(active),
                              body->triangulation().get_communicator(),
                              ArrayView<double>(active));
          std::vector<double> of_level(finest + 1, 0.);
          of_level[finest] = active[finest];
          for (unsigned int l = finest; l-- > 0;)
            of_level[l] = active[l] + of_level[l + 1] /
                                        GeometryInfo<2>::max_children_per_cell;
          double below = 0;
          for (unsigned int l = 0; l <= finest; ++l)
            {
              cells[l] += below + of_level[l];
              below += active[l];
            }
        }
      return cells;
    }



    // Which cell levels the nested start solves, coarsest first: the
    // finest with at most two thirds of the cycle's cells, then going
    // down, each with at most a third of the one above (at most
    // @p n_levels). Why not simply the levels below the finest: a mesh
    // adapted from an already adapted one has few cells in its finest
    // levels (punch, 502,848 DoFs: the four levels below the finest had
    // 329,000-493,000 DoFs, each as dear as the cycle, the coarsest 9
    // Newton steps cold). Why two thirds: with a quarter the levels are as
    // coarse at the contact zone as the uniform ones (punch, 28,722 DoFs:
    // 5 Newton steps from the level of 7,764 DoFs, 2 from that of 12,818,
    // 45 %); with a half that 502,848-DoF cycle got the level of 119,976
    // DoFs and took 5 steps, from that of 328,636 (65 %) 3, and the whole
    // run 41 -> 34 s.
    std::vector<unsigned int>
    coarser_cell_levels(const std::array<const ElasticBody *, 2> &bodies,
                        const unsigned int                        finest,
                        const unsigned int                        n_levels)
    {
      std::vector<unsigned int> levels;
      if (finest == 0 || n_levels == 0)
        return levels;
      const std::vector<double> cells = cells_up_to_level(bodies, finest);
      for (unsigned int L = finest; L-- > 0 && levels.size() < n_levels;)
        if (levels.empty() ? cells[L] <= 2 * cells[finest] / 3 :
                             cells[L] <= cells[levels.back()] / 3)
          levels.push_back(L);
      std::reverse(levels.begin(), levels.end());
      return levels;
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
        solve_level(
          bodies, contact_parameters, solver_parameters, states, level, levels);
      }
    return states;
  }



  std::vector<ContactNodeState>
  predict_contact_sets_on_coarser_hierarchy(
    const MPI_Comm                            mpi_communicator,
    const Scene                              &scene,
    const CellType                            cell_type,
    const std::array<const ElasticBody *, 2> &fine_bodies,
    const unsigned int                        n_levels,
    const parameters::FiniteElements         &fe_parameters,
    const parameters::Contact                &contact_parameters,
    const parameters::LinearSolver           &solver_parameters,
    std::vector<NestedIterationLevel>        &levels)
  {
    levels.clear();
    unsigned int finest = 0;
    for (unsigned int b = 0; b < 2; ++b)
      finest =
        std::max(finest, fine_bodies[b]->triangulation().n_global_levels() - 1);
    const std::vector<unsigned int> cell_levels =
      coarser_cell_levels(fine_bodies, finest, n_levels);
    if (cell_levels.empty())
      return {};
    // The rebuilt hierarchies need only the refined cells below the finest
    // of their levels (refine_as): the parents of the cycle's finest cells
    // are not gathered (punch refine 0.25 %: 49,150 cell ids of 75,370 on
    // the block, 4,984 of 7,210 on the punch).
    std::array<std::set<CellId>, 2> refined;
    for (unsigned int b = 0; b < 2; ++b)
      refined[b] = fine_bodies[b]->refined_cells(cell_levels.back());
    // The levels are built as every other body is (make_bodies(): the
    // scene's coarse meshes, manifolds and boundary ids) and refined by the
    // cycle's refined cell ids, which gives the same meshes on any number
    // of ranks; copying the cycle's meshes (copy_triangulation) and
    // coarsening them level by level would need an ElasticBody built from
    // another one's triangulation.
    std::vector<ContactNodeState> states;
    const ElasticBodies           bodies =
      make_bodies(mpi_communicator, scene, cell_type, 0, fe_parameters);
    for (const unsigned int L : cell_levels)
      {
        for (unsigned int b = 0; b < 2; ++b)
          bodies[b]->refine_as(refined[b], L);
        NestedIterationLevel level;
        level.from_own_hierarchy = true;
        level.finest_cell_level  = L;
        solve_level(
          bodies, contact_parameters, solver_parameters, states, level, levels);
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
        level.coarsening        = k;
        level.every_size_scaled = scene.coarser_meshes_scale_every_size();
        solve_level(
          bodies, contact_parameters, solver_parameters, states, level, levels);
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
