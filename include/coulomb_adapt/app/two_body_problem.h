#ifndef coulomb_adapt_app_two_body_problem_h
#define coulomb_adapt_app_two_body_problem_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/output/body_output.h>
#include <coulomb_adapt/output/contact_output.h>
#include <coulomb_adapt/output/run_summary.h>
#include <coulomb_adapt/scenes/scene.h>

#include <array>
#include <memory>

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
    TwoBodyProblem(const MPI_Comm     mpi_communicator,
                   const Parameters & parameters,
                   ParameterHandler & prm,
                   const std::string &parameter_file);

    void
    run();

  private:
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
    void
    compare_with_exact_error(const unsigned int cycle);
    void
    output_results(const unsigned int cycle);
    void
    refine_grid();

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
    nlohmann::json                            cycle_record;
  };
} // namespace coulomb_adapt

#endif
