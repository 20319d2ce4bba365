#include <deal.II/base/utilities.h>

#include <coulomb_adapt/contact/newton_diagnostics.h>
#include <coulomb_adapt/core/parameter_error.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace coulomb_adapt
{
  namespace newton_diagnostics
  {
    namespace
    {
      std::string
      newton_step(const unsigned int step)
      {
        return "Newton step " + std::to_string(step);
      }



      // The hint of the "would slide" diagnosis: at the first step the
      // load itself is suspect; later also the iteration.
      std::string
      sliding_message(const double       friction_coefficient,
                      const unsigned int step)
      {
        if (friction_coefficient == 0)
          return "can slide freely along the frictionless interface: nothing "
                 "holds it tangentially. Hold it with the scene's hold option "
                 "(blocks, punch: 'Hold centre line'; hertz: 'Hold axis'; "
                 "patch: 'Hold upper body') or use friction.";
        return "would slide: in the contact sets of this step every active "
               "node slips and no Dirichlet data hold it tangentially, so "
               "the linear system is singular. " +
               (step == 1 ?
                  std::string("") :
                  std::string("If the tangential load exceeds mu times "
                              "the normal load the static problem has no "
                              "equilibrium; otherwise the active set "
                              "iteration went astray (try another "
                              "'Contact/Complementarity scale').")) +
               (step == 1 ? std::string("The tangential load exceeds mu "
                                        "times the normal load?") :
                            std::string());
      }



      // Why body 1, free of Dirichlet data, has no active node. The
      // iteration starts with the nodes nearest to body 2 closed among
      // those that face it (ContactSolver::initialize_sets), so none at the
      // first step means that no node of body 1's contact curve lies
      // opposite body 2's: the curves can never touch, whatever the load.
      // Later the solve has said which nodes face body 2, and the ones
      // that do have opened: the load pulls body 1 away, or body 2 gives
      // way (body 2 is checked after body 1, so a floating body 2 that
      // moves with it shows here too).
      std::string
      unheld_message(const std::vector<ContactNodeState> &states,
                     const unsigned int                   step,
                     const std::string                   &why_nothing_faces)
      {
        unsigned int n_facing     = 0;
        double       smallest_gap = std::numeric_limits<double>::max();
        for (const auto &s : states)
          if (s.facing_master)
            {
              ++n_facing;
              smallest_gap = std::min(smallest_gap, s.gap);
            }
        // A node that still touches (its gap at round-off against the
        // others') while all have opened: the body turns about it, pressed
        // down elsewhere by a load that the contact cannot hold there.
        double                  largest_gap = 0, position_scale = 0;
        const ContactNodeState *pivot = nullptr;
        for (const auto &s : states)
          if (s.facing_master)
            {
              largest_gap    = std::max(largest_gap, std::abs(s.gap));
              position_scale = std::max(position_scale, s.position.norm());
              if (pivot == nullptr || s.gap < pivot->gap)
                pivot = &s;
            }
        // Every gap still closed (round-off against the coordinates): the
        // nodes opened on their tension, not on a gap, and no node is a
        // pivot among open ones. (A pure pull was diagnosed as a tipping
        // load about a node with gap -2.8e-18 mm, "up to 2.8e-18 mm
        // elsewhere".)
        const bool gaps_at_round_off = largest_gap <= 1e-10 * position_scale;
        std::ostringstream m;
        m << std::setprecision(3) << "has no active contact node and no "
          << "Dirichlet support: nothing holds it. ";
        if (step > 1 && n_facing > 0 && pivot != nullptr &&
            !gaps_at_round_off && pivot->gap <= 1e-10 * largest_gap)
          m << "Its contact nodes have all opened, but the one at ("
            << pivot->position[0] << ", " << pivot->position[1]
            << ") still touches body 2 (gap " << pivot->gap << " mm, up to "
            << largest_gap << " mm elsewhere): the body "
            << "turns about that point, away from body 2. Its load tips "
            << "it: the load acts outside the zone the contact can "
            << "support (over an edge), and no static equilibrium exists "
            << "for it. Check where the load acts and where the bodies "
            << "touch.";
        else if ((step == 1 || n_facing == 0) && !why_nothing_faces.empty())
          m << "None of the " << states.size() << " nodes of its contact "
            << "curve lies opposite body 2's contact curve: "
            << why_nothing_faces;
        else if (step == 1 || n_facing == 0)
          m << "None of the " << states.size() << " nodes of its contact "
            << "curve lies opposite body 2's contact curve: the two curves "
            << "do not face each other and cannot touch. Check where the "
            << "contact curves lie and which curves the contact groups "
            << "name.";
        else if (gaps_at_round_off)
          m << "The " << n_facing << " of its contact nodes that face body "
            << "2 all pull on it (their gaps are still closed, at most "
            << largest_gap << " mm): its load pulls it away from body 2 "
            << "(is it loaded towards body 2?), or body 2 gives way under "
            << "it (are body 2's Dirichlet data enough to hold it?).";
        else
          m << "The " << n_facing << " of its contact nodes that face body "
            << "2 have all opened (smallest gap " << smallest_gap
            << " mm): its load pulls it away from body 2 (is it loaded "
            << "towards body 2?), or body 2 gives way under it (are body "
            << "2's Dirichlet data enough to hold it?).";
        return m.str();
      }



      // Up to ten positions of the nodes in @p changed.
      std::string
      node_positions(const std::vector<ContactNodeState> &states,
                     const std::vector<unsigned int>     &changed,
                     const std::string                   &before,
                     const std::string                   &after)
      {
        std::ostringstream s;
        for (unsigned int i = 0; i < std::min<std::size_t>(changed.size(), 10);
             ++i)
          s << before << states[changed[i]].position[0] << ", "
            << states[changed[i]].position[1] << after;
        return s.str();
      }
    } // namespace



    void
    check_support(const SlaveSupport                  &support,
                  const std::vector<ContactNodeState> &states,
                  const double                         friction_coefficient,
                  const unsigned int                   step,
                  const std::string                   &body_name,
                  const std::string                   &why_nothing_faces)
    {
      unsigned int n_active = 0;
      for (const auto &s : states)
        n_active += (s.status != ContactStatus::open);
      const std::string where =
        newton_step(step) + ": body 1 (" + body_name + ") ";
      if (n_active == 0 && !support.holds_all_rigid_motions())
        throw ContactDiagnosis(
          where + unheld_message(states, step, why_nothing_faces), step - 1);
      check_sliding(support.slip_motion_free(states),
                    states,
                    friction_coefficient,
                    step,
                    "body 1 (" + body_name + ")");
    }



    // Every active node slips: each fixes only its normal gap, the
    // tangential traction follows from the pressure (mu p), and nothing
    // but the normals and the Dirichlet data resists a rigid motion. If a
    // rigid motion keeps every normal gap (the normals of a flat interface
    // all parallel, those of a circle all through its centre), the system
    // is singular, and the sets have no equilibrium: along that motion
    // friction resists with mu p at every node, and the load would have to
    // equal that exactly. If the normals hold every rigid motion (two
    // flanks of a wedge, a dovetail), the body is held although every node
    // slips: the normal forces of the flanks balance the load in the
    // directions their friction cannot, and the solve goes on (the force
    // balance of the converged sets is checked at the end).
    void
    check_sliding(const bool                           rigid_motion_free,
                  const std::vector<ContactNodeState> &states,
                  const double                         friction_coefficient,
                  const unsigned int                   step,
                  const std::string                   &body_label)
    {
      unsigned int n_active = 0, n_stick = 0;
      for (const auto &s : states)
        if (s.status != ContactStatus::open)
          {
            ++n_active;
            n_stick += (s.status == ContactStatus::stick);
          }
      if (n_stick == 0 && n_active > 0 && rigid_motion_free)
        throw ContactDiagnosis(newton_step(step) + ": " + body_label + " " +
                                 sliding_message(friction_coefficient, step),
                               step - 1);
    }



    ContactDiagnosis
    krylov_failure(const unsigned int                  step,
                   const SolverControl::NoConvergence &e)
    {
      return ContactDiagnosis(
        newton_step(step) + ": the iterative linear solver did not converge (" +
          std::to_string(e.last_step) +
          " iterations, the limit 'Linear solver/Maximum iterations'; "
          "residual " +
          Utilities::to_string(e.last_residual) +
          "). Use 'Linear solver/Type = direct' for the contact system, or "
          "raise 'Linear solver/Maximum iterations'.",
        step);
    }



    ContactDiagnosis
    linear_solve_failure(const unsigned int    step,
                         const unsigned int    n_active,
                         const bool            rotation_free,
                         const std::exception &e)
    {
      return ContactDiagnosis(
        newton_step(step) +
          ": the linear solve failed with these contact sets (" +
          std::to_string(n_active) + " active nodes). " +
          (rotation_free ?
             std::string("These sets and the Dirichlet data leave body "
                         "1's rotation free (a singular system): hold "
                         "the body or refine the mesh where the bodies "
                         "touch.") :
             std::string(
               "The most likely cause is that body 1 is not held: all "
               "its contact nodes are open or slipping in the same "
               "direction, and no Dirichlet data holds it (a load "
               "beyond the friction limit, or mu = 0 without a "
               "lateral support).")) +
          " Solver message: " + user_message(e),
        step);
    }



    ContactDiagnosis
    residual_above_tolerance(const unsigned int step,
                             const double       residual,
                             const double       tolerance,
                             const double       floor)
    {
      return ContactDiagnosis(
        "The contact sets have converged after " + std::to_string(step) +
          " Newton steps, but the complementarity residual " +
          Utilities::to_string(residual) + " stays above the tolerance " +
          Utilities::to_string(tolerance) +
          " and above the round-off of the multipliers (" +
          Utilities::to_string(floor) +
          "): the linear solver is not accurate enough for it "
          "(ill-conditioned system?). Relax 'Contact/Tolerance' or check "
          "the data.",
        step);
    }



    ContactDiagnosis
    cycling(const unsigned int                   step,
            const unsigned int                   repeated,
            const std::vector<double>           &residual_history,
            const std::vector<ContactNodeState> &states,
            const std::vector<unsigned int>     &changed,
            const unsigned int                   n_damping_steps,
            const bool                           iterative_solver_chosen)
    {
      std::ostringstream residuals;
      for (const double r : residual_history)
        residuals << r << ' ';
      // The residual after a set change compares the gaps it opens with
      // the displacements the pressures make: of order 1 (up to the ratio
      // of the element sizes) in a regular system. Sets that do not hold
      // body 1 leave its motion to round-off, and the residual grows by
      // 1 / eps. Above the geometric mean of the two, 1 / sqrt(eps), some
      // sets of the cycle cannot hold the body: the iteration alternates
      // between sets that hold it and sets that do not because no set
      // holds it in equilibrium, which no complementarity constant changes.
      std::vector<unsigned int> singular_steps;
      double                    largest = 0;
      for (unsigned int k = repeated + 1;
           k <= std::min<std::size_t>(step, residual_history.size());
           ++k)
        if (residual_history[k - 1] >
            1 / std::sqrt(std::numeric_limits<double>::epsilon()))
          {
            singular_steps.push_back(k);
            largest = std::max(largest, residual_history[k - 1]);
          }
      if (!singular_steps.empty())
        {
          std::ostringstream s;
          s << std::setprecision(3)
            << "The semismooth Newton iteration cycles: after step " << step
            << " the contact sets repeat those of step " << repeated
            << ". Last residuals: " << residuals.str() << "; in step(s)";
          for (const unsigned int k : singular_steps)
            s << ' ' << k;
          s << " of the cycle the residual reached " << largest
            << ": those sets did not hold body 1 (a singular system, whose "
               "solution is round-off). No contact set holds it in "
               "equilibrium: the load has no static equilibrium on these "
               "contact curves (a load outside the zone the contact can "
               "support tips the body over an edge; a tangential load above "
               "mu times the normal load makes it slide), and another "
               "'Contact/Complementarity scale' does not change that. Check "
               "where the load acts and where the bodies touch.";
          return ContactDiagnosis(s.str(), step);
        }
      return ContactDiagnosis(
        "The semismooth Newton iteration cycles: after step " +
          std::to_string(step) + " the contact sets repeat those of step " +
          std::to_string(repeated) + ". Last residuals: " + residuals.str() +
          "; nodes that flipped in the last step: " +
          node_positions(states, changed, "(", ") ") +
          ". c_n, c_t were "
          "reduced " +
          std::to_string(n_damping_steps) +
          " times ten-fold before. Try another 'Contact/Complementarity "
          "scale'" +
          (iterative_solver_chosen ?
             ", or 'Linear solver/Type = direct' (an inexact iterative "
             "solve can make the sets cycle)" :
             std::string()) +
          ".",
        step);
    }



    ContactDiagnosis
    iteration_limit(const unsigned int                   max_steps,
                    const std::vector<double>           &residual_history,
                    const std::vector<ContactNodeState> &states,
                    const std::vector<unsigned int>     &changed,
                    const unsigned int                   n_turning_steps)
    {
      std::ostringstream s;
      s << "The semismooth Newton iteration did not converge in " << max_steps
        << " steps (the limit 'Contact/Maximum Newton iterations'). Residual "
           "history:";
      for (const double r : residual_history)
        s << ' ' << r;
      s << ". Nodes that changed set in the last step:"
        << node_positions(states, changed, " (", ")");
      if (n_turning_steps > 0)
        s << ". In " << n_turning_steps
          << " of the steps the sets and the Dirichlet data left body 1's "
             "rotation free (a single active node, or normals meeting in "
             "one point): a singular system, which the linear solver may "
             "answer with a wild iterate. Hold the body or refine the mesh "
             "where the bodies touch";
      else
        s << ". If the residual was still falling, raise 'Contact/Maximum "
             "Newton iterations'";
      return ContactDiagnosis(s.str(), max_steps);
    }



    void
    log_newton_step(const ConditionalOStream          &pcout,
                    const unsigned int                 step,
                    const ContactSolverReport         &report,
                    const double                       friction_coefficient,
                    const SetChangeControl::SetUpdate &update,
                    const double                       residual,
                    const double                       assembly_time,
                    const double                       solve_time,
                    const LinearSolverReport          *linear_solve)
    {
      pcout << "    Newton " << std::setw(2) << step << ": " << std::setw(4)
            << report.n_active << " active";
      if (friction_coefficient > 0)
        pcout << " (" << report.n_stick << " stick, " << report.n_slip
              << " slip)";
      pcout << ", " << update.n_changed << " changed";
      if (update.n_moved != update.n_changed)
        pcout << " (" << update.n_moved << " moved)";
      pcout << ", residual " << std::scientific << std::setprecision(2)
            << residual << std::defaultfloat << " (assembly "
            << std::setprecision(2) << assembly_time << " s, solve "
            << solve_time << " s";
      if (linear_solve != nullptr)
        pcout << ", " << linear_solve->method << " "
              << linear_solve->n_iterations << " its"
              << (linear_solve->preconditioner_reused ? ", AMG reused" : "");
      pcout << ")" << std::endl;
    }



    void
    log_convergence(const ConditionalOStream &pcout,
                    const bool                rotation_free,
                    const double              residual,
                    const double              tolerance,
                    const double              floor)
    {
      if (rotation_free)
        pcout << "    warning: the converged sets leave body 1's "
                 "rotation free, so its displacement is determined "
                 "only up to a small rigid rotation (stresses and "
                 "tractions do not depend on it); refine the mesh "
                 "where the bodies touch, or hold the body"
              << std::endl;
      if (residual > tolerance)
        pcout << "    residual " << residual << " is above the "
              << "tolerance " << tolerance
              << " but within the round-off of the multipliers (" << floor
              << "): converged" << std::endl;
    }
  } // namespace newton_diagnostics
} // namespace coulomb_adapt
