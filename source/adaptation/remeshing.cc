#include <coulomb_adapt/adaptation/adaptation_strategy.h>
#include <coulomb_adapt/adaptation/gmsh_remesher.h>

#include <memory>

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
  // coarse mesh), with the nodal size field of the plan. gmsh (serial, one
  // per process) meshes the bodies one after the other on rank 0 in a
  // background thread, while the main thread does the rest: the second
  // body's size field while gmsh meshes the first, the first body's
  // deal.II mesh while gmsh meshes the second. The meshes are the same as
  // one body after the other.
  void
  Remeshing::change_meshes(const std::array<ElasticBody *, 2> &bodies,
                           const ErrorEstimate &,
                           const OptimalSizeRatios      &ratios,
                           const parameters::Adaptation &parameters,
                           const unsigned int,
                           const double,
                           MeshAdaptationReport &) const
  {
    std::array<Triangulation<2>, 2>               geometry;
    std::array<std::vector<SizeFieldTriangle>, 2> field;
    auto start = [&](const unsigned int b) {
      return std::make_unique<GmshRemeshing>(
        geometry[b],
        field[b],
        bodies[b]->name(),
        bodies[b]->dof_handler().get_communicator(),
        parameters.remeshing_algorithm,
        bodies[b]->description().interior_lines(),
        bodies[b]->description().support_points);
    };
    for (unsigned int b = 0; b < 2; ++b)
      bodies[b]->create_scene_coarse_mesh(geometry[b]);
    field[0]     = nodal_size_field(*bodies[0], ratios.ratio[0]);
    auto running = start(0);
    field[1]     = nodal_size_field(*bodies[1], ratios.ratio[1]);
    const CoarseMeshData first = running->finish();
    running                    = start(1);
    bodies[0]->replace_mesh(first);
    bodies[1]->replace_mesh(running->finish());
  }



  namespace
  {
    const bool registered =
      register_mesh_adaptation_strategy(AdaptationStrategy::remesh,
                                        std::make_unique<Remeshing>());
  } // namespace
} // namespace coulomb_adapt
