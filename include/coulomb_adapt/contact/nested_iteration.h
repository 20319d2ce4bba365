#ifndef coulomb_adapt_contact_nested_iteration_h
#define coulomb_adapt_contact_nested_iteration_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/scene.h>

#include <array>
#include <vector>

namespace coulomb_adapt
{
  /** One coarser mesh of a nested iteration, for the log and summary.json. */
  struct NestedIterationLevel
  {
    unsigned int global_refinements = 0;
    /** For graded meshes: the level's graded zone is 2^coarsening times
     * coarser than the fine mesh's (0 for uniform refinement levels). */
    unsigned int coarsening = 0;
    /** With coarsening > 0: every mesh size scaled by 2^coarsening (a
     * .geo file's meshes), not only a graded zone. */
    bool every_size_scaled = false;
    /** Whether the level is an adapted cycle's own meshes with their
     * cells beyond finest_cell_level coarsened. */
    bool                    from_own_hierarchy = false;
    unsigned int            finest_cell_level  = 0;
    types::global_dof_index n_dofs             = 0;
    /** Of a load path: the largest count of its load steps. */
    unsigned int newton_iterations = 0;
    unsigned int n_active          = 0;
    double       wall_time         = 0;
    /** Of a load path (predict_load_path_on_coarser_meshes()), one count
     * per load step; empty for a static solve. */
    std::vector<unsigned int> newton_iterations_per_load_step;
  };

  /**
   * Initial contact sets for a static contact solve on the scene's mesh
   * with @p fine_refinements uniform refinements, from the same problem
   * solved on the @p n_levels meshes below it (nested iteration): the
   * coarsest from the initial gap, each finer one warm-started from the
   * sets of the one before. When that is the scene's own mesh
   * (@p n_levels = @p fine_refinements) and the scene grades it, that mesh
   * starts in turn from the scene's coarser gradings
   * (predict_contact_sets_on_coarser_graded_meshes(), 'Contact/Nested
   * iteration levels' of them): cold, hertz's own meshes take 7-8 Newton
   * steps.
   *
   * Why: started from the initial gap, the active set of the first Newton
   * step is about twice the final contact zone, and the following steps
   * release only a band of nodes at its edges each, so the step count grows
   * with the number of nodes across the zone (hertz: 8 steps at 9e3 DoFs,
   * 11 at 1.4e5). A coarser mesh gets the zone right to within its own
   * node spacing at a fraction of the cost, and the fine solve then only
   * corrects the edges. The final solution does not depend on where the
   * sets start: the fine Newton iteration runs to its own convergence.
   *
   * @p levels receives what each coarser solve did.
   */
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
    std::vector<NestedIterationLevel> &levels);

  /**
   * The same for first meshes that are not uniform refinements of coarser
   * ones but graded by the scene (hertz: towards the contact point, gmsh's
   * size field for triangles): the coarser levels are the scene's meshes
   * with the graded zone 2^k times coarser, k = @p n_levels ... 1
   * (Scene::with_coarser_graded_meshes()). The sets are carried from level
   * to level by the nodes' positions, as between uniform levels. Returns
   * no sets (and no levels) when the scene has no coarser graded meshes.
   */
  std::vector<ContactNodeState>
  predict_contact_sets_on_coarser_graded_meshes(
    const MPI_Comm                     mpi_communicator,
    const Scene                       &scene,
    const CellType                     cell_type,
    const unsigned int                 n_levels,
    const parameters::FiniteElements  &fe_parameters,
    const parameters::Contact         &contact_parameters,
    const parameters::LinearSolver    &solver_parameters,
    std::vector<NestedIterationLevel> &levels);

  /**
   * The same for a cycle whose meshes @p fine_bodies are local
   * (hanging-node) refinements of the scene's coarse meshes (Q1/Q2,
   * 'Adaptation/Strategy = refine'; the driver keeps the uniform levels
   * for a scene that grades its meshes): the coarser levels are those meshes
   * with every cell beyond level L coarsened (rebuilt from the scene's
   * coarse meshes, ElasticBody::refine_as()), for up to @p n_levels
   * levels L: the finest with at most two thirds of the cycle's cells, each
   * coarser one with at most a third of the one above; coarsest first, the
   * coarsest from the initial gap.
   *
   * Why: a locally refined mesh resolves the contact zone much finer than
   * a uniform one of its DoFs, so the uniform levels' sets are coarse
   * there (punch, refine, epsilon_0 = 0.5 %: from the uniform level of
   * 7,764 DoFs, 33 active nodes, the 28,722-DoF cycle with 83 took 5
   * Newton steps, the stick/slip front moving 17, 4, 4, 2 nodes). Its
   * own level of 12,818 DoFs resolves the zone nearly as the cycle does
   * (51 active nodes), and the fine solve then took 2 steps.
   */
  std::vector<ContactNodeState>
  predict_contact_sets_on_coarser_hierarchy(
    const MPI_Comm                            mpi_communicator,
    const Scene                              &scene,
    const CellType                            cell_type,
    const std::array<const ElasticBody *, 2> &fine_bodies,
    const unsigned int                        n_levels,
    const parameters::FiniteElements         &fe_parameters,
    const parameters::Contact                &contact_parameters,
    const parameters::LinearSolver           &solver_parameters,
    std::vector<NestedIterationLevel>        &levels);

  /**
   * Nested iteration along a load path (a scene with n_load_steps() > 1,
   * cattaneo): the whole path is solved on each coarser mesh of
   * predict_contact_sets_on_coarser_meshes() (@p graded: of
   * predict_contact_sets_on_coarser_graded_meshes()), coarsest first; each
   * load step of a finer level starts from the sets of the same load step
   * one level down (the coarsest: from its own step before, moved on by
   * the load-step predictor where the scene allows it). Returns the sets
   * of the finest coarser level at the end of each load step (index step
   * - 1), the start of the fine mesh's load steps; empty, with no levels,
   * when there is no coarser mesh.
   *
   * Why: a load step that moves the slip front over many nodes takes a
   * Newton step per band of nodes from the step before's sets (cattaneo
   * Q1, 1.4e5 DoFs: 6 in the first tangential step, 5 in the later ones
   * with the predictor); a coarser mesh moves the front at a fraction of
   * the cost. The history (the tangential jump at the end of the step
   * before) stays with each mesh's own solver, so every level solves its
   * own discrete path, and the fine one converges to the cold start's.
   */
  std::vector<std::vector<ContactNodeState>>
  predict_load_path_on_coarser_meshes(
    const MPI_Comm                     mpi_communicator,
    const Scene                       &scene,
    const CellType                     cell_type,
    const unsigned int                 fine_refinements,
    const unsigned int                 n_levels,
    const bool                         graded,
    const parameters::FiniteElements  &fe_parameters,
    const parameters::Contact         &contact_parameters,
    const parameters::LinearSolver    &solver_parameters,
    std::vector<NestedIterationLevel> &levels);
} // namespace coulomb_adapt

#endif
