#ifndef coulomb_adapt_app_two_body_problem_h
#define coulomb_adapt_app_two_body_problem_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/table_handler.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/adaptation/target_calibration.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/output/body_output.h>
#include <coulomb_adapt/output/contact_output.h>
#include <coulomb_adapt/output/run_summary.h>
#include <coulomb_adapt/scenes/scene.h>

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
    /** The log goes to @p log on rank 0 (tests pass a string stream). */
    TwoBodyProblem(const MPI_Comm     mpi_communicator,
                   const Parameters & parameters,
                   ParameterHandler & prm,
                   const std::string &parameter_file,
                   std::ostream &     log = std::cout);

    void
    run();

    /** Body @p b (0: upper/slave, 1: lower/master) on its last mesh. */
    const ElasticBody &
    body(const unsigned int b) const;

    /** The indicator of the last cycle. */
    const ErrorEstimate &
    last_error_estimate() const;

  private:
    /** Refuse, before any mesh is built, first meshes above 'Adaptation/
     * Maximum number of DoFs' (estimated from the coarse meshes), a body
     * of one cell (a blind zz/spr indicator) and a body 1 more than 1e8
     * times stiffer than body 2. */
    void
    check_initial_mesh_size() const;
    /** Remove the per-cycle output files of an earlier run from the output
     * directory (rank 0; the log says how many). */
    void
    remove_files_of_earlier_run() const;
    /** Where the meshes come from, for messages ("gmsh file 'x.msh': "),
     * empty for the built-in scenes. */
    std::string mesh_source;
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
    /** Nested iteration for the first Newton step: the sets predicted on
     * the coarser meshes, or false if skipped. */
    bool
    start_from_coarser_meshes(std::vector<ContactNodeState> &predicted_sets);
    void
    solve_separately();
    void
    estimate_error();
    void
    compare_with_exact_error(const unsigned int cycle);
    void
    output_results(const unsigned int cycle, const bool last_cycle);
    /** Adapt both meshes for the next cycle (Adaptation/Strategy). */
    void
    refine_grid();
    /** Whether another cycle is wanted after @p cycle, with the reason. */
    bool
    continue_cycles(const unsigned int      cycle,
                    const types::global_dof_index n_dofs,
                    std::string &           reason) const;

    MPI_Comm                                  mpi_communicator;
    const Parameters &                        parameters;
    ConditionalOStream                        pcout;
    TimerOutput                               computing_timer;
    std::unique_ptr<Scene>                    scene;
    std::array<std::unique_ptr<ElasticBody>, 2> bodies;
    std::array<std::unique_ptr<BodyOutput>, 2>  body_outputs;
    std::unique_ptr<RunSummary>               summary;
    std::unique_ptr<ContactSolver>            contact_solver;
    std::unique_ptr<ContactOutput>            contact_output;
    std::unique_ptr<ErrorEstimate>            error_estimate;
    /** With `Compare estimators`: the other estimators on the same
     * solution (they do not drive the adaptation). */
    std::vector<std::unique_ptr<ErrorEstimate>> compared_estimates;
    nlohmann::json                            cycle_record;
    /** The contact sets of the previous cycle, for the warm start. */
    std::vector<ContactNodeState>             previous_contact_states;
    /** The adaptation that made the current meshes (none on cycle 0). */
    std::optional<MeshAdaptationReport>       last_adaptation;
    /** epsilon_0 corrected by what the previous plans achieved. */
    TargetCalibration                         target_calibration;
    /** One row per cycle, printed at the end. */
    TableHandler                              cycle_table;
  };
} // namespace coulomb_adapt

#endif
