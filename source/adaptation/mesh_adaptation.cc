#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/gmsh_remesher.h>
#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/adaptation/optimal_size.h>
#include <coulomb_adapt/adaptation/refinement_flags.h>

namespace coulomb_adapt
{
  MeshAdaptationReport
  adapt_meshes(const std::array<ElasticBody *, 2>  &bodies,
               ErrorEstimate                       &estimate,
               const std::vector<ContactNodeState> &contact_states,
               const parameters::Adaptation        &parameters,
               const unsigned int                   degree,
               const double                         aimed_error)
  {
    MeshAdaptationReport report;
    report.strategy = parameters.strategy;
    // The recovered stresses live on the meshes about to change; what
    // follows needs only the cells' epsilon_E.
    for (auto &recovered : estimate.recovered)
      recovered.reset();
    if (parameters.strategy == "uniform")
      {
        for (ElasticBody *body : bodies)
          body->refine_uniformly();
        return report;
      }

    const std::array<const ElasticBody *, 2> const_bodies = {
      {bodies[0], bodies[1]}};
    const bool use_ratios = parameters.strategy == "remesh" ||
                            parameters.refinement_criterion == "size ratio";
    OptimalSizeRatios ratios;
    if (use_ratios)
      {
        // 'Maximum number of DoFs' bounds the next mesh too, as a cell
        // count at the current DoFs per cell (the element and cell type do
        // not change between cycles).
        double n_cells = 0, n_dofs = 0;
        for (const ElasticBody *body : const_bodies)
          {
            n_cells += body->triangulation().n_global_active_cells();
            n_dofs += body->dof_handler().n_dofs();
          }
        const double max_n_cells   = parameters.max_dofs * n_cells / n_dofs;
        ratios                     = optimal_size_ratios(const_bodies,
                                     estimate,
                                     find_singular_points(const_bodies,
                                                          contact_states),
                                     aimed_error,
                                     degree,
                                     parameters.singular_rate,
                                     parameters.min_size_ratio,
                                     parameters.max_size_ratio,
                                     max_n_cells);
        report.aimed_epsilon       = aimed_error;
        report.predicted_n_cells   = ratios.predicted_n_cells;
        report.predicted_epsilon   = ratios.predicted_epsilon;
        report.n_singular_cells    = ratios.n_singular_cells;
        report.n_at_min_ratio      = ratios.n_at_min_ratio;
        report.n_at_max_ratio      = ratios.n_at_max_ratio;
        report.limited_by_max_dofs = ratios.limited_by_max_n_cells;
      }

    if (parameters.strategy == "remesh")
      {
        for (unsigned int b = 0; b < 2; ++b)
          {
            const auto field = nodal_size_field(*bodies[b], ratios.ratio[b]);
            Triangulation<2> geometry;
            bodies[b]->create_scene_coarse_mesh(geometry);
            bodies[b]->replace_mesh(
              remesh_with_gmsh(geometry,
                               field,
                               bodies[b]->name(),
                               bodies[b]->dof_handler().get_communicator(),
                               parameters.remeshing_algorithm,
                               bodies[b]->description().interior_lines(),
                               bodies[b]->description().support_points));
          }
        return report;
      }

    const RefinementDecisions decisions =
      use_ratios ? decisions_from_size_ratios(const_bodies,
                                              estimate,
                                              ratios,
                                              aimed_error) :
                   decisions_from_indicator(const_bodies,
                                            estimate,
                                            parameters.refinement_criterion,
                                            parameters.refine_fraction,
                                            parameters.coarsen_fraction,
                                            degree);
    for (unsigned int b = 0; b < 2; ++b)
      for (const signed char d : decisions[b])
        {
          report.n_refine_flags += (d > 0);
          report.n_coarsen_flags += (d < 0);
        }
    const MPI_Comm comm    = bodies[0]->dof_handler().get_communicator();
    report.n_refine_flags  = Utilities::MPI::sum(report.n_refine_flags, comm);
    report.n_coarsen_flags = Utilities::MPI::sum(report.n_coarsen_flags, comm);
    for (unsigned int b = 0; b < 2; ++b)
      bodies[b]->refine_and_coarsen(decisions[b]);
    return report;
  }
} // namespace coulomb_adapt
