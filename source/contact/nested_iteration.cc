#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/nested_iteration.h>

#include <iostream>
#include <memory>

namespace coulomb_adapt
{
  namespace
  {
    // Solve the contact problem on @p bodies (set up and assembled here),
    // warm-started from @p states when there are any; @p states receives
    // the solution's sets and @p level what the solve did.
    void
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
      const ContactSolverReport report = solver.solve();
      states                           = solver.node_states();
      timer.stop();
      level.n_dofs =
        bodies[0]->dof_handler().n_dofs() + bodies[1]->dof_handler().n_dofs();
      level.newton_iterations = report.newton_iterations;
      level.n_active          = report.n_active;
      level.wall_time         = timer.wall_time();
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
    const unsigned int  coarsest = fine_refinements - n_levels;
    const ElasticBodies bodies =
      make_bodies(mpi_communicator, scene, cell_type, coarsest, fe_parameters);

    std::vector<ContactNodeState> states;
    for (unsigned int r = coarsest; r < fine_refinements; ++r)
      {
        if (r > coarsest)
          for (auto &body : bodies)
            body->refine_uniformly();
        NestedIterationLevel level;
        level.global_refinements = r;
        solve_level(
          bodies, contact_parameters, solver_parameters, states, level);
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
        const std::unique_ptr<Scene> coarser =
          scene.with_coarser_graded_meshes(k);
        if (!coarser)
          return {};
        const ElasticBodies bodies =
          make_bodies(mpi_communicator, *coarser, cell_type, 0, fe_parameters);
        NestedIterationLevel level;
        level.coarsening = k;
        solve_level(
          bodies, contact_parameters, solver_parameters, states, level);
        levels.push_back(level);
      }
    return states;
  }
} // namespace coulomb_adapt
