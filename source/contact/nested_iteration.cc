#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/nested_iteration.h>

#include <iostream>
#include <memory>

namespace coulomb_adapt
{
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
    // The coarse solves' Newton lines would drown the fine one's: each
    // level is reported by the caller in one line instead.
    const ConditionalOStream silent(std::cout, false);

    const unsigned int  coarsest = fine_refinements - n_levels;
    const ElasticBodies bodies =
      make_bodies(mpi_communicator, scene, cell_type, coarsest, fe_parameters);

    std::vector<ContactNodeState> states;
    for (unsigned int r = coarsest; r < fine_refinements; ++r)
      {
        Timer timer;
        if (r > coarsest)
          for (auto &body : bodies)
            body->refine_uniformly();
        for (auto &body : bodies)
          {
            body->setup_system();
            body->assemble_system();
          }
        ContactSolver solver(*bodies[0],
                             *bodies[1],
                             contact_parameters,
                             solver_parameters,
                             silent);
        if (!states.empty())
          solver.warm_start_from(states);
        const ContactSolverReport report = solver.solve();
        states                           = solver.node_states();
        timer.stop();
        levels.push_back({r,
                          bodies[0]->dof_handler().n_dofs() +
                            bodies[1]->dof_handler().n_dofs(),
                          report.newton_iterations,
                          report.n_active,
                          timer.wall_time()});
      }
    return states;
  }
} // namespace coulomb_adapt
