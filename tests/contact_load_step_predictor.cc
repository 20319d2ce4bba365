// The load step predictor (ContactSolver::predict_next_load_step) on
// cattaneo's load path (the Hertz contact, then the holder moved sideways
// in 5 equal steps): from the third load step on, the sets start from the
// last step's state moved on by its increments (multipliers, gaps,
// slips) instead of from the last step's sets. Run side by side with the
// path without the predictor, every load step must end with
//  - the same solution: the same node-wise sets, pressure and tangential
//    traction within 1e-8 of the largest pressure, displacements within
//    1e-8 relative (the Newton iteration runs to its own convergence);
//  - at most 4 Newton steps in the predicted steps, and never more than
//    without the predictor (whose later steps take up to 6 on the finer
//    meshes).
// The first two load steps are not predicted and must be identical.
// Run on 1 and 2 ranks with the same output.

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  void
  compare_load_path(
    const std::string                                      &name,
    const std::vector<std::pair<std::string, std::string>> &settings,
    ConditionalOStream                                     &out)
  {
    auto               previous  = testing::solve_contact_setup(settings);
    auto               predicted = testing::solve_contact_setup(settings);
    const unsigned int n_steps   = predicted->scene->n_load_steps();
    AssertThrow(n_steps == 6, ExcInternalError());
    std::ostringstream steps;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        for (auto *p : {previous.get(), predicted.get()})
          {
            p->scene->set_load_step(step);
            for (auto &body : p->bodies)
              {
                body->setup_system();
                body->assemble_system();
              }
          }
        const double ratio = predicted->scene->load_increment_ratio(step);
        AssertThrow((step >= 3) == (ratio == 1.), ExcInternalError());
        if (ratio > 0)
          predicted->solver->predict_next_load_step(ratio);
        previous->report  = previous->solver->solve();
        predicted->report = predicted->solver->solve();

        const std::string where = name + ", load step " + std::to_string(step);
        testing::assert_same_contact_solution(where, *previous, *predicted);
        const unsigned int n_previous = previous->report.newton_iterations;
        const unsigned int n          = predicted->report.newton_iterations;
        AssertThrow(predicted->report.newton_iterations_of_stopped_prediction ==
                      0,
                    ExcMessage(where + ": the predicted start stopped"));
        AssertThrow(step < 3 ? n == n_previous : (n <= 4 && n <= n_previous),
                    ExcMessage(where + ": Newton steps without the predictor " +
                               std::to_string(n_previous) + ", with it " +
                               std::to_string(n)));
        steps << " " << n_previous << "/" << n;
      }
    out << name << ": " << predicted->solver->node_states().size()
        << " slave nodes; Newton steps per load step without / with the "
           "predictor:"
        << steps.str()
        << "; same sets, tractions within 1e-8, displacements within 1e-8 "
           "in every load step"
        << std::endl;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  compare_load_path("cattaneo Q1", {{"Scene/Name", "cattaneo"}}, out);
  compare_load_path("cattaneo P1, 1 global refinement",
                    {{"Scene/Name", "cattaneo"},
                     {"Mesh/Cell type", "triangle"},
                     {"Mesh/Global refinements", "1"}},
                    out);
}
