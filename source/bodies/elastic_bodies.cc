#include <coulomb_adapt/bodies/elastic_bodies.h>

namespace coulomb_adapt
{
  ElasticBodies
  make_bodies(const MPI_Comm                    mpi_communicator,
              const Scene                      &scene,
              const CellType                    cell_type,
              const unsigned int                global_refinements,
              const parameters::FiniteElements &fe_parameters)
  {
    ElasticBodies bodies;
    for (unsigned int b = 0; b < 2; ++b)
      bodies[b] = std::make_unique<ElasticBody>(mpi_communicator,
                                                scene,
                                                b,
                                                cell_type,
                                                global_refinements,
                                                fe_parameters);
    return bodies;
  }



  ElasticBodies
  make_bodies(const MPI_Comm     mpi_communicator,
              const Scene       &scene,
              const Parameters  &parameters,
              const unsigned int global_refinements)
  {
    return make_bodies(mpi_communicator,
                       scene,
                       parameters.mesh.cell_type,
                       global_refinements,
                       parameters.finite_elements);
  }



  std::array<const ElasticBody *, 2>
  body_pointers(const ElasticBodies &bodies)
  {
    return {{bodies[0].get(), bodies[1].get()}};
  }
} // namespace coulomb_adapt
