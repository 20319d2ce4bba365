#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/adaptation_strategy.h>
#include <coulomb_adapt/adaptation/contact_size_cap.h>
#include <coulomb_adapt/adaptation/gmsh_remesher.h>
#include <coulomb_adapt/adaptation/triangle_split.h>

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
  //
  // gmsh is one instance per process, so on two or more ranks the bodies
  // are meshed at the same time on different ones: body b on rank
  // b mod n_ranks, each with its own gmsh. Every collective step (the
  // gathers of the size fields, the broadcasts of the meshes, the new
  // triangulations) comes before or after all the gmsh calls, so that no
  // rank waits in one while another meshes. The field does not depend on
  // the rank it is gathered on, so the meshes are those of one rank.
  //
  // A body whose field asks for more than 'Remeshing split above cells'
  // cells is meshed by gmsh with 2^k times the sizes and split k times
  // (triangle_split.h), on the rank that meshes it, before the broadcast.
  // The contact size cap is a cap on the final sizes: it comes first.
  void
  Remeshing::change_meshes(const std::array<ElasticBody *, 2> &bodies,
                           const ErrorEstimate &,
                           const OptimalSizeRatios      &ratios,
                           const parameters::Adaptation &parameters,
                           const unsigned int            degree,
                           const double,
                           MeshAdaptationReport &report) const
  {
    std::array<unsigned int, 2>                   root;
    std::array<std::vector<SizeFieldTriangle>, 2> fields;
    std::array<Triangulation<2>, 2>               geometries;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const MPI_Comm comm = bodies[b]->dof_handler().get_communicator();
        root[b]             = b % Utilities::MPI::n_mpi_processes(comm);
        fields[b] = nodal_size_field(*bodies[b], ratios.ratio[b], root[b]);
        bodies[b]->create_scene_coarse_mesh(geometries[b]);
      }
    // P1's contact surfaces are polygons; P2's faces follow the curve.
    if (degree == 1)
      cap_master_contact_sizes(bodies, root, fields);

    // A large body is meshed by gmsh 2^k times coarser and split k times
    // (triangle_split.h): gmsh's time is per triangle.
    std::array<GmshMeshing, 2>  meshings;
    std::array<unsigned int, 2> n_splits = {{0, 0}};
    for (unsigned int b = 0; b < 2; ++b)
      if (Utilities::MPI::this_mpi_process(
            bodies[b]->dof_handler().get_communicator()) == root[b])
        {
          n_splits[b] =
            n_triangle_splits(size_field_cell_count(fields[b]),
                              parameters.remeshing_split_above_cells);
          coarsen_size_field(fields[b], n_splits[b]);
          meshings[b] =
            mesh_with_gmsh_here(geometries[b],
                                fields[b],
                                bodies[b]->name(),
                                parameters.remeshing_algorithm,
                                bodies[b]->description().interior_lines(),
                                bodies[b]->description().support_points,
                                n_splits[b]);
          fields[b] = {};
        }

    for (unsigned int b = 0; b < 2; ++b)
      {
        const MPI_Comm comm = bodies[b]->dof_handler().get_communicator();
        bodies[b]->replace_mesh(
          share_gmsh_mesh(meshings[b], bodies[b]->name(), comm, root[b]));
        report.n_triangle_splits[b] =
          Utilities::MPI::broadcast(comm, n_splits[b], root[b]);
      }
  }



  namespace
  {
    const bool registered =
      register_mesh_adaptation_strategy(AdaptationStrategy::remesh,
                                        std::make_unique<Remeshing>());
  } // namespace
} // namespace coulomb_adapt
