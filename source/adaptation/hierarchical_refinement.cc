#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/adaptation_strategy.h>
#include <coulomb_adapt/adaptation/refinement_flags.h>

#include <algorithm>

namespace coulomb_adapt
{
  namespace
  {
    /** Quadrilaterals refined and coarsened with hanging nodes ('refine'): the
     * cells chosen from the size ratios or by the indicator ('Refinement
     * criterion'). */
    class HierarchicalRefinement : public MeshAdaptationStrategy
    {
    public:
      bool
      plans_optimal_mesh(
        const parameters::Adaptation &parameters) const override;

      void
      change_meshes(const std::array<ElasticBody *, 2> &bodies,
                    const ErrorEstimate                &estimate,
                    const OptimalSizeRatios            &ratios,
                    const parameters::Adaptation       &parameters,
                    const unsigned int                  degree,
                    const double                        aimed_error,
                    MeshAdaptationReport               &report) const override;
    };
  } // namespace



  bool
  HierarchicalRefinement::plans_optimal_mesh(
    const parameters::Adaptation &parameters) const
  {
    return parameters.refinement_criterion == RefinementCriterion::size_ratio;
  }



  // The optimal mesh rounded to whole levels (decisions_from_size_ratios),
  // or the cells chosen from epsilon_E by one of the classical criteria.
  void
  HierarchicalRefinement::change_meshes(
    const std::array<ElasticBody *, 2> &bodies,
    const ErrorEstimate                &estimate,
    const OptimalSizeRatios            &ratios,
    const parameters::Adaptation       &parameters,
    const unsigned int                  degree,
    const double                        aimed_error,
    MeshAdaptationReport               &report) const
  {
    const std::array<const ElasticBody *, 2> const_bodies = {
      {bodies[0], bodies[1]}};
    const RefinementDecisions decisions =
      plans_optimal_mesh(parameters) ?
        // A plan held to 'Maximum number of DoFs' aims at what that many
        // cells reach: aiming at epsilon_0 itself, the rounding threshold
        // grew until nearly every cell was refined (punch, cap 20,000: a
        // plan of 9,610 cells gave 29,140 cells, 59,916 DoFs).
        decisions_from_size_ratios(const_bodies,
                                   estimate,
                                   ratios,
                                   ratios.limited_by_max_n_cells ?
                                     std::max(aimed_error,
                                              ratios.predicted_epsilon) :
                                     aimed_error) :
        decisions_from_indicator(const_bodies,
                                 estimate,
                                 parameters.refinement_criterion,
                                 parameters.refine_fraction,
                                 parameters.coarsen_fraction,
                                 degree);
    // Coarsening counts the owned cells that can coarsen: a cell of the
    // coarse mesh (level 0) asked to coarsen stays as it is.
    for (unsigned int b = 0; b < 2; ++b)
      for (const auto &cell :
           bodies[b]->triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const signed char d = decisions[b][cell->active_cell_index()];
            report.n_refine_flags += (d > 0);
            report.n_coarsen_flags += (d < 0 && cell->level() > 0);
          }
    const MPI_Comm comm    = bodies[0]->dof_handler().get_communicator();
    report.n_refine_flags  = Utilities::MPI::sum(report.n_refine_flags, comm);
    report.n_coarsen_flags = Utilities::MPI::sum(report.n_coarsen_flags, comm);
    for (unsigned int b = 0; b < 2; ++b)
      bodies[b]->refine_and_coarsen(decisions[b]);
  }



  const bool registered = register_mesh_adaptation_strategy(
    AdaptationStrategy::refine,
    std::make_unique<HierarchicalRefinement>());
} // namespace coulomb_adapt
