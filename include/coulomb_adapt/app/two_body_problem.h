#ifndef coulomb_adapt_app_two_body_problem_h
#define coulomb_adapt_app_two_body_problem_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/adaptation/target_calibration.h>
#include <coulomb_adapt/app/load_scaling.h>
#include <coulomb_adapt/app/target_claim.h>
#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_solve_driver.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/output/body_output.h>
#include <coulomb_adapt/output/contact_output.h>
#include <coulomb_adapt/output/cycle_report.h>
#include <coulomb_adapt/scenes/scaled_scene.h>

#include <array>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The program: a scene's two bodies, solved over a sequence of cycles,
   * in the shape of deal.II's step-40 (`run()` calling `setup_system`,
   * `assemble_system`, `solve`, `output_results`, `refine_grid`).
   *
   * Scenes with a contact interface are solved by the ContactSolver (mortar
   * + semismooth Newton); scenes without one (manufactured) solve each
   * body on its own, and a body without Dirichlet support is reported as
   * such before anything is solved.
   */
  class TwoBodyProblem
  {
  public:
    /** Declare every entry of the program: the subsections of Parameters
     * and the scenes' subsection `Scene`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** The log goes to @p log on rank 0 (tests pass a string stream). */
    TwoBodyProblem(const MPI_Comm     mpi_communicator,
                   const Parameters  &parameters,
                   ParameterHandler  &prm,
                   const std::string &parameter_file,
                   std::ostream      &log = std::cout);

    /** The cycles; an error in them is recorded in summary.json
     * (`status` "failed", `error`, `failed_in_cycle`) and rethrown. */
    void
    run();

    /** Body @p b (0: upper/slave, 1: lower/master) on its last mesh. */
    const ElasticBody &
    body(const unsigned int b) const;

    /** The indicator of the last cycle. */
    const ErrorEstimate &
    last_error_estimate() const;

  private:
    /** run() without the failure record. */
    void
    run_cycles();

    /** The bodies on the scene's meshes, their output and the contact
     * driver. */
    void
    make_bodies();
    /** The scales of the run (core/units.h), on the first meshes (set
     * up): none where every scale is comfortable; the loads divided by P
     * where only they are extreme and there is no initial gap; else
     * choose_scales_for_moduli. Logs its choice. */
    void
    choose_load_scale(const LoadStressScale &loads);
    /** Moduli and loads divided together (units::scales_for_moduli), for
     * extreme moduli or strains or an initial gap (choose_load_scale calls
     * it), the bodies made again with the scaled moduli; a ParameterError
     * before anything is solved where the strains are beyond 1e+-300, or
     * where displacements must be scaled but the contact curves have an
     * initial gap. @p message is the log line begun, @p source the
     * scene's file and load entries. */
    void
    choose_scales_for_moduli(const LoadStressScale &loads,
                             std::ostringstream    &message,
                             const std::string     &source);
    void
    setup_system();
    void
    assemble_system();
    void
    solve();
    bool
    has_contact() const;
    void
    solve_contact();
    void
    solve_separately();
    void
    estimate_error();
    /** Each body's strain energy (summary.json), once per cycle. */
    std::array<double, 2>
    record_strain_energies();
    void
    compare_with_exact_error(const std::array<double, 2> &strain_energies);
    void
    compare_with_exact_displacements();
    void
    output_results(const unsigned int cycle, const bool last_cycle);
    /** Completes the fields of a cycle written in the background
     * (Output/Write in background); whether there was one. Collective. */
    bool
    complete_background_writes();
    /** The fields' indexes (.pvd, .xdmf) of the cycles complete so far. */
    void
    write_field_indexes();
    /** Adapt both meshes for the next cycle (Adaptation/Strategy). */
    void
    refine_grid();
    /** What this cycle's estimate claims (a bound or not) and, where it
     * was computed, its exact error (target_claim.h). */
    TargetClaim
    target_claim() const;
    /** Whether another cycle is wanted after @p cycle, with the reason. */
    bool
    continue_cycles(const unsigned int            cycle,
                    const types::global_dof_index n_dofs,
                    std::string                  &reason) const;
    std::array<const ElasticBody *, 2>
    body_pointers() const;

    /** Where the meshes come from, for messages ("gmsh file 'x.msh': "),
     * empty for the built-in scenes. */
    std::string                                mesh_source;
    MPI_Comm                                   mpi_communicator;
    const Parameters                          &parameters;
    ConditionalOStream                         pcout;
    TimerOutput                                computing_timer;
    std::unique_ptr<ScaledScene>               scene;
    ElasticBodies                              bodies;
    std::array<std::unique_ptr<BodyOutput>, 2> body_outputs;
    /** The last cycle whose bodies' fields are all written (Output/Write
     * in background), none before the first. */
    std::optional<unsigned int> fields_complete_through;
    /** The log lines and summary.json record of each cycle. */
    std::unique_ptr<CycleReport>        cycle_report;
    std::unique_ptr<ContactSolveDriver> contact_solve_driver;
    std::unique_ptr<ContactSolver>      contact_solver;
    std::unique_ptr<ContactOutput>      contact_output;
    std::unique_ptr<ErrorEstimate>      error_estimate;
    /** With `Compare estimators`: the other estimators on the same
     * solution (they do not drive the adaptation). */
    std::vector<std::unique_ptr<ErrorEstimate>> compared_estimates;
    /** The contact sets of the previous cycle, for the warm start. */
    std::vector<ContactNodeState> previous_contact_states;
    /** The cycle being computed (for the failure record). */
    unsigned int current_cycle = 0;
    /** The adaptation that made the current meshes (none on cycle 0). */
    std::optional<MeshAdaptationReport> last_adaptation;
    /** Each body's cell count on the previous cycle's meshes (none on
     * cycle 0): a remesh that returns the same counts cannot coarsen
     * further. */
    std::optional<std::array<types::global_cell_index, 2>>
      previous_cycle_n_cells;
    /** epsilon_0 corrected by what the previous plans achieved. */
    TargetCalibration target_calibration;
  };
} // namespace coulomb_adapt

#endif
