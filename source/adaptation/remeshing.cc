#include <coulomb_adapt/adaptation/adaptation_strategy.h>
#include <coulomb_adapt/adaptation/gmsh_remesher.h>

namespace coulomb_adapt
{
  namespace
  {
    /** Each body remeshed by gmsh with the optimal size field
     * h*_E = r_E h_E ('remesh'). */
    class Remeshing : public MeshAdaptationStrategy
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
  Remeshing::plans_optimal_mesh(const parameters::Adaptation &) const
  {
    return true;
  }



  // Each body's new mesh is made by gmsh on the scene's geometry (its
  // coarse mesh), with the nodal size field of the plan.
  void
  Remeshing::change_meshes(const std::array<ElasticBody *, 2> &bodies,
                           const ErrorEstimate &,
                           const OptimalSizeRatios      &ratios,
                           const parameters::Adaptation &parameters,
                           const unsigned int,
                           const double,
                           MeshAdaptationReport &) const
  {
    for (unsigned int b = 0; b < 2; ++b)
      {
        const auto       field = nodal_size_field(*bodies[b], ratios.ratio[b]);
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
  }



  namespace
  {
    const bool registered =
      register_mesh_adaptation_strategy(AdaptationStrategy::remesh,
                                        std::make_unique<Remeshing>());
  } // namespace
} // namespace coulomb_adapt
