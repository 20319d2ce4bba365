#include <coulomb_adapt/adaptation/adaptation_strategy.h>
#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/adaptation/optimal_size.h>

#include <cmath>

namespace coulomb_adapt
{
  namespace
  {
    // The optimal mesh of theory.md section 4 for @p aimed_error, its
    // predictions and bounds recorded in @p report. 'Maximum number of
    // DoFs' bounds the next mesh too, as a cell count at the current DoFs
    // per cell (the element and cell type do not change between cycles).
    OptimalSizeRatios
    plan_optimal_mesh(const std::array<const ElasticBody *, 2> &bodies,
                      const ErrorEstimate                      &estimate,
                      const std::vector<ContactNodeState>      &contact_states,
                      const parameters::Adaptation             &parameters,
                      const unsigned int                        degree,
                      const double                              aimed_error,
                      const bool                                model_checked,
                      MeshAdaptationReport                     &report)
    {
      double n_cells = 0, n_dofs = 0;
      for (const ElasticBody *body : bodies)
        {
          n_cells += body->triangulation().n_global_active_cells();
          n_dofs += body->dof_handler().n_dofs();
        }
      const double max_n_cells = parameters.max_dofs * n_cells / n_dofs;
      const OptimalSizePlanner planner(bodies,
                                       estimate,
                                       find_singular_points(bodies,
                                                            contact_states),
                                       degree,
                                       parameters.singular_rate);
      const auto               plan = [&](const double min_size_ratio) {
        report.min_size_ratio = min_size_ratio;
        return planner.plan(aimed_error,
                            min_size_ratio,
                            parameters.max_size_ratio,
                            max_n_cells,
                            parameters.min_cells);
      };
      OptimalSizeRatios ratios = plan(parameters.min_size_ratio);
      // A plan limited by the cell count is short of its aim anyway.
      if (model_checked && !ratios.limited_by_max_n_cells &&
          ratios.n_at_min_ratio > 0 &&
          ratios.predicted_epsilon > aimed_error * (1 + 1e-6))
        {
          report.unrelaxed_predicted_epsilon = ratios.predicted_epsilon;
          ratios = plan(std::pow(parameters.min_size_ratio, 1.5));
        }
      report.aimed_epsilon        = aimed_error;
      report.predicted_n_cells    = ratios.predicted_n_cells;
      report.predicted_epsilon    = ratios.predicted_epsilon;
      report.n_singular_cells     = ratios.n_singular_cells;
      report.n_at_min_ratio       = ratios.n_at_min_ratio;
      report.n_at_max_ratio       = ratios.n_at_max_ratio;
      report.limited_by_max_dofs  = ratios.limited_by_max_n_cells;
      report.limited_by_min_cells = ratios.limited_by_min_n_cells;
      return ratios;
    }
  } // namespace



  MeshAdaptationReport
  adapt_meshes(const std::array<ElasticBody *, 2>  &bodies,
               ErrorEstimate                       &estimate,
               const std::vector<ContactNodeState> &contact_states,
               const parameters::Adaptation        &parameters,
               const unsigned int                   degree,
               const double                         aimed_error,
               const bool                           model_checked)
  {
    MeshAdaptationReport report;
    report.strategy = parameters.strategy;
    // The recovered stresses live on the meshes about to change; what
    // follows needs only the cells' epsilon_E.
    for (auto &recovered : estimate.recovered)
      recovered.reset();

    const MeshAdaptationStrategy &strategy =
      mesh_adaptation_strategy(parameters.strategy);
    OptimalSizeRatios ratios;
    if (strategy.plans_optimal_mesh(parameters))
      ratios = plan_optimal_mesh({{bodies[0], bodies[1]}},
                                 estimate,
                                 contact_states,
                                 parameters,
                                 degree,
                                 aimed_error,
                                 model_checked,
                                 report);
    strategy.change_meshes(
      bodies, estimate, ratios, parameters, degree, aimed_error, report);
    return report;
  }
} // namespace coulomb_adapt
