#ifndef coulomb_adapt_contact_contact_solve_driver_h
#define coulomb_adapt_contact_contact_solve_driver_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/nested_iteration.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/scene.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** Whether the nested iteration of a first cycle ran, and what each
   * coarser mesh did, or why it was skipped. */
  struct NestedIterationRecord
  {
    std::vector<NestedIterationLevel> levels;
    /** Empty if the coarser solves ran. */
    std::string skipped;
  };

  /** What a contact solve of one cycle did, from its start to its last
   * load step, for the log and summary.json (CycleReport). */
  struct ContactSolveOutcome
  {
    /** The solver that converged: its node states, multipliers and mortar
     * interface are those of the bodies' solutions. */
    std::unique_ptr<ContactSolver> solver;
    /** Its report, with the Newton steps summed over the load steps. */
    ContactSolverReport report;
    bool                warm_start = false;
    /** Set when nested iteration was considered (first meshes without
     * warm start, or a cycle after a large refinement). */
    std::optional<NestedIterationRecord> nested_iteration;
    /** The summary keys of the restarts taken, in order. */
    std::vector<std::string> restarts;
    /** Newton steps of the starts that stopped with a diagnosis. */
    unsigned int newton_iterations_of_stopped_starts = 0;
    unsigned int n_load_steps                        = 1;
    /** Newton steps of the converged start in each load step. */
    std::vector<unsigned int> newton_iterations_per_load_step;
    /** The contact moment (ContactSolverReport) at the end of each load
     * step. */
    std::vector<double> contact_moment_per_load_step;
    /** Largest overlap and largest clearance of the initial gap (mm). */
    double             initial_overlap   = 0;
    double             initial_clearance = 0;
    LinearSolverReport linear_solver;
    /** Under 'Linear solver/Type = auto': the failed Krylov solve of this
     * run after which the direct solver took the Newton systems
     * (KrylovFailureRecord; empty if none failed). */
    std::string krylov_failure;
  };

  /**
   * The contact solve of one cycle around the ContactSolver's Newton
   * iteration: where the first Newton step takes its sets from (the
   * previous cycle's sets, the coarser meshes' sets, or the initial gap),
   * where a static solve goes on when it stops with a diagnosis (the
   * restarts), and the scene's load path (one step for the static problem,
   * several for a quasi-static one). Progress goes to the log as it
   * happens; the outcome is returned for the cycle's report.
   */
  class ContactSolveDriver
  {
  public:
    ContactSolveDriver(const MPI_Comm                      mpi_communicator,
                       const Scene                        &scene,
                       const std::array<ElasticBody *, 2> &bodies,
                       const Parameters                   &parameters,
                       const ConditionalOStream           &pcout);

    /**
     * Solve the contact problem on the bodies' current (assembled) systems.
     * @p previous_states are the previous cycle's sets (empty if none; on
     * a load path the driver starts from the sets its own last solve had
     * after the first load step instead);
     * @p first_meshes says the bodies still have the scene's meshes with
     * 'Mesh/Global refinements', whose coarser versions the nested
     * iteration solves. Throws the last ContactDiagnosis when every start
     * stopped.
     */
    ContactSolveOutcome
    solve(const std::vector<ContactNodeState> &previous_states,
          const bool                           first_meshes);

  private:
    /** One more start of a static solve that stopped with a diagnosis. */
    struct Restart
    {
      parameters::Contact contact;
      bool                from_predicted_sets;
      std::string         description;
      std::string         summary_key;
    };

    /** A new solver with contact parameters @p c, from the initial gap or
     * from @p predicted_sets. */
    std::unique_ptr<ContactSolver>
    new_solver(const parameters::Contact           &c,
               const std::vector<ContactNodeState> *predicted_sets) const;
    /** The restarts a static solve may take, in order. */
    std::vector<Restart>
    restarts(const bool predicted_start) const;
    /** Nested iteration: the sets predicted on the coarser meshes in
     * @p predicted_sets and true, or false with the reason in @p record. */
    bool
    start_from_coarser_meshes(std::vector<ContactNodeState> &predicted_sets,
                              NestedIterationRecord         &record);
    /** Whether the cycle's meshes, with @p n_dofs, are so much finer than
     * the previous solve's that the previous sets are too coarse a start
     * ('Adaptation/Nested start above DoF ratio'). */
    bool
    after_large_refinement(const types::global_dof_index n_dofs) const;
    /** Nested iteration for a cycle after a large refinement: the scene's
     * meshes refined uniformly, up to the finest with at most @p n_dofs
     * (estimated); as start_from_coarser_meshes(). */
    bool
    start_from_uniform_refinements(
      const types::global_dof_index  n_dofs,
      std::vector<ContactNodeState> &predicted_sets,
      NestedIterationRecord         &record);
    /** Why a cycle with @p n_dofs takes the nested start, for the log. */
    std::string
    nested_start_reason(const types::global_dof_index n_dofs) const;
    /** Whether a nested start takes the cycle's own hierarchy (meshes
     * refined in place, a scene that does not grade them) rather than
     * uniform refinements of the scene's meshes. */
    bool
    start_from_own_hierarchy() const;
    /** The same for locally refined (quadrilateral) meshes: the cycle's
     * own meshes with their finest levels coarsened
     * (predict_contact_sets_on_coarser_hierarchy()). */
    bool
    start_from_coarser_hierarchy(const types::global_dof_index  n_dofs,
                                 std::vector<ContactNodeState> &predicted_sets,
                                 NestedIterationRecord         &record);
    /** The load steps of the scene, each restarted as @p restarts allow. */
    void
    solve_load_steps(const std::vector<Restart>          &restarts,
                     const std::vector<ContactNodeState> &predicted_sets,
                     ContactSolveOutcome                 &outcome);
    /** Largest overlap and clearance of the initial gap. */
    void
    measure_initial_gap(ContactSolveOutcome &outcome) const;

    const MPI_Comm                     mpi_communicator;
    const Scene                       &scene;
    const std::array<ElasticBody *, 2> bodies;
    const Parameters                  &parameters;
    /** A load path's sets after its first load step, from the last solve:
     * the next cycle's start (the last step's slip zone is no guess for
     * the first step's). */
    std::vector<ContactNodeState> first_load_step_states;
    /** A load path's sets at the end of each load step on the finest
     * coarser mesh of the nested iteration (first meshes only; else
     * empty): the start of the fine mesh's load steps. */
    std::vector<std::vector<ContactNodeState>> coarser_load_path;
    /** DoFs of the last solve (0 before the first), and of the scene's
     * meshes with 'Mesh/Global refinements' (0 if this driver never solved
     * on them): the measures of a large refinement and of the uniform
     * refinements' sizes. */
    types::global_dof_index   last_n_dofs       = 0;
    types::global_dof_index   first_meshes_dofs = 0;
    const ConditionalOStream &pcout;
    /** Shared by every ContactSolver of the fine meshes in this run: after
     * one failed Krylov solve under 'auto' the direct solver takes the
     * Newton systems (the following load steps, restarts and cycles). */
    const std::shared_ptr<KrylovFailureRecord> krylov_failures =
      std::make_shared<KrylovFailureRecord>();
  };
} // namespace coulomb_adapt

#endif
