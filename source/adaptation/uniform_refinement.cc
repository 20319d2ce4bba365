#include <coulomb_adapt/adaptation/adaptation_strategy.h>

namespace coulomb_adapt
{
  namespace
  {
    /** Every cell refined once ('uniform'). */
    class UniformRefinement : public MeshAdaptationStrategy
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
  UniformRefinement::plans_optimal_mesh(const parameters::Adaptation &) const
  {
    return false;
  }



  void
  UniformRefinement::change_meshes(const std::array<ElasticBody *, 2> &bodies,
                                   const ErrorEstimate &,
                                   const OptimalSizeRatios &,
                                   const parameters::Adaptation &,
                                   const unsigned int,
                                   const double,
                                   MeshAdaptationReport &) const
  {
    for (ElasticBody *body : bodies)
      body->refine_uniformly();
  }



  namespace
  {
    const bool registered =
      register_mesh_adaptation_strategy(AdaptationStrategy::uniform,
                                        std::make_unique<UniformRefinement>());
  } // namespace
} // namespace coulomb_adapt
