#ifndef coulomb_adapt_bodies_elastic_bodies_h
#define coulomb_adapt_bodies_elastic_bodies_h

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/scene.h>

#include <array>
#include <memory>

namespace coulomb_adapt
{
  /** The two bodies of a problem: 0 the upper, slave body, 1 the lower,
   * master body (Scene). */
  using ElasticBodies = std::array<std::unique_ptr<ElasticBody>, 2>;

  /**
   * Both bodies of @p scene on its coarse meshes of @p cell_type, refined
   * uniformly @p global_refinements times, not yet set up: the one way the
   * program, nested iteration and the tests make a problem's bodies.
   */
  ElasticBodies
  make_bodies(const MPI_Comm                    mpi_communicator,
              const Scene                      &scene,
              const CellType                    cell_type,
              const unsigned int                global_refinements,
              const parameters::FiniteElements &fe_parameters);

  /** The same, with the mesh and element of @p parameters. */
  ElasticBodies
  make_bodies(const MPI_Comm     mpi_communicator,
              const Scene       &scene,
              const Parameters  &parameters,
              const unsigned int global_refinements);

  /** The bodies as the solvers and estimators take them. */
  std::array<const ElasticBody *, 2>
  body_pointers(const ElasticBodies &bodies);
} // namespace coulomb_adapt

#endif
