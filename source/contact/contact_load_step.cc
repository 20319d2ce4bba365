#include <deal.II/base/tensor.h>

#include <coulomb_adapt/contact/active_set.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>

#include <algorithm>
#include <string>

namespace coulomb_adapt
{
  // One load step of a contact solve: where its Newton iteration starts
  // (the sets of the step before, or predicted from that step's
  // increments along a proportional load path), the iteration itself
  // (ContactSolver::iterate), and what the step leaves for the next one.

  // A load step with predicted sets (predict_next_load_step, or a later
  // load step's sets from a coarser mesh, warm_start_from) that stops
  // with a diagnosis is solved again from the previous step's sets: the
  // prediction is a guess, and a wrong guess is not the problem's failure.
  ContactSolverReport
  ContactSolver::solve()
  {
    // A later load step (the states of the one before exist) with sets
    // from a coarser mesh (warm_start_from) is predicted as well.
    const bool transferred = !warm_start_states.empty() && !states.empty();
    setup();
    // The near null space depends on the meshes only: once per load step,
    // and only for the AMG path.
    near_null_space =
      iterative ? rigid_body_modes() : std::vector<std::vector<double>>();

    const bool extrapolated = !transferred && predictor_ratio > 0 &&
                              !load_step_start.empty() &&
                              last_increments.size() == states.size();
    const bool          predicted = extrapolated || transferred;
    ContactSolverReport report;
    if (extrapolated)
      {
        report.n_predicted_changes = predict_sets();
        pcout << "  contact: sets predicted from the last load step's "
                 "increments: "
              << report.n_predicted_changes << " nodes changed" << std::endl;
      }
    predictor_ratio = 0;
    try
      {
        iterate(report);
      }
    catch (const ContactDiagnosis &e)
      {
        if (!predicted)
          throw;
        pcout << "  contact: the predicted sets stopped after "
              << e.newton_steps << " Newton steps ("
              << std::string(e.what()).substr(0, 160)
              << " ...); solving the load step again from the sets of the "
                 "step before"
              << std::endl;
        const unsigned int n_stopped           = e.newton_steps;
        states                                 = load_step_start;
        const unsigned int n_predicted_changes = report.n_predicted_changes;
        report                                 = ContactSolverReport();
        report.n_predicted_changes             = n_predicted_changes;
        report.newton_iterations_of_stopped_prediction = n_stopped;
        iterate(report);
      }
    // Kept until here: iterate() tells a start from the initial gap by it.
    warm_start_states.clear();
    finish_load_step(report);
    return report;
  }



  void
  ContactSolver::predict_next_load_step(const double increment_ratio)
  {
    predictor_ratio = increment_ratio;
  }



  // The increments of this load step are those the next one's predictor
  // extrapolates; the first load step on these meshes has none (its
  // start is no converged state).
  void
  ContactSolver::finish_load_step(ContactSolverReport &report)
  {
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        states[j].slip_increment =
          slip_increment(states[j], previous_weighted_slip[j]);
        previous_weighted_slip[j] = states[j].slip * states[j].weight;
      }
    last_increments.clear();
    if (load_step_start.size() == states.size())
      for (unsigned int j = 0; j < states.size(); ++j)
        last_increments.push_back(
          {states[j].pressure - load_step_start[j].pressure,
           states[j].tangential_traction -
             load_step_start[j].tangential_traction,
           states[j].gap - load_step_start[j].gap,
           states[j].slip_increment});
    for (const auto &s : states)
      {
        const Tensor<1, 2> force =
          -s.weight *
          (s.pressure * s.normal + s.tangential_traction * s.tangent);
        report.contact_force += force;
        report.contact_moment +=
          s.position[0] * force[1] - s.position[1] * force[0];
        report.max_contact_pressure =
          std::max(report.max_contact_pressure, s.pressure);
      }
  }
} // namespace coulomb_adapt
