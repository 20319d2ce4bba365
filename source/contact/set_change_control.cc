#include <coulomb_adapt/contact/set_change_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace coulomb_adapt
{
  namespace
  {
    unsigned char
    status_bit(const char signature)
    {
      return signature == 'o' ? 1 :
             signature == 't' ? 2 :
             signature == '+' ? 4 :
                                8;
    }
  } // namespace



  SetChangeControl::SetChangeControl(
    ActiveSetRule                 &rule,
    std::vector<ContactNodeState> &states,
    const std::vector<double>     &previous_weighted_slip,
    const SlaveSupport            &support,
    const bool                     restriction_allowed,
    const ConditionalOStream      &pcout)
    : rule(rule)
    , states(states)
    , previous_weighted_slip(previous_weighted_slip)
    , support(support)
    , restriction_allowed(restriction_allowed)
    , pcout(pcout)
    , history({set_signature(states)})
    , statuses_held(states.size(), 0)
    , best_changed(std::numeric_limits<unsigned int>::max())
    , best_residual(std::numeric_limits<double>::max())
  {}



  void
  SetChangeControl::begin_step(const unsigned int k)
  {
    if (k > 1)
      {
        const std::string sets = set_signature(states);
        for (unsigned int j = 0; j < sets.size(); ++j)
          statuses_held[j] |= status_bit(sets[j]);
      }
  }



  SetChangeControl::SetUpdate
  SetChangeControl::update_sets(const unsigned int k)
  {
    SetUpdate         update;
    const std::string before = set_signature(states);
    states_before            = states;
    update.n_changed =
      coulomb_adapt::update_sets(rule, previous_weighted_slip, states);

    const std::string proposed = set_signature(states);
    for (unsigned int j = 0; j < proposed.size(); ++j)
      if (proposed[j] != before[j] &&
          (statuses_held[j] & status_bit(proposed[j])) != 0)
        ++update.n_reversed;

    update.n_moved = restricted && update.n_changed > 0 ?
                       restrict_set_changes(rule,
                                            previous_weighted_slip,
                                            states_before,
                                            restricted_fraction,
                                            states) :
                       update.n_changed;
    // After step 1 only where friction can hold the body: its sets come
    // from the initial gap or a prediction, and a body that slides is
    // diagnosed at once, not after the kept steps.
    if (update.n_changed > 0)
      keep_body_held(k == 1);

    const std::string after = set_signature(states);
    for (unsigned int j = 0; j < after.size(); ++j)
      if (after[j] != before[j])
        update.changed.push_back(j);
    return update;
  }



  std::optional<unsigned int>
  SetChangeControl::repeated_step() const
  {
    const auto seen =
      std::find(history.begin(), history.end(), set_signature(states));
    if (seen == history.end())
      return std::nullopt;
    return seen - history.begin();
  }



  bool
  SetChangeControl::damp(const unsigned int k, const unsigned int repeated)
  {
    if (n_damping >= max_damping_steps)
      return false;
    ++n_damping;
    for (double &c : rule.complementarity_constant)
      c *= 0.1;
    coulomb_adapt::update_sets(rule, previous_weighted_slip, states);
    if (restricted)
      restrict_set_changes(rule,
                           previous_weighted_slip,
                           states_before,
                           restricted_fraction,
                           states);
    if (k > 1)
      keep_body_held(false);
    pcout << "    the sets repeat those of step " << repeated
          << ": c_n, c_t reduced to " << std::pow(0.1, n_damping)
          << " times their value (damped set changes)" << std::endl;
    history.assign(1, set_signature(states));
    // The damping deals with this cycle: the stagnation test starts again.
    n_stalled     = 0;
    was_reversing = false;
    return true;
  }



  // Stagnation: no new low of the changed nodes or of the residual for
  // stagnation_window steps, and in each of the last two steps most
  // changes undo earlier ones. Both conditions keep the restriction out of
  // iterations that converge without it: an iteration that shrinks its
  // sets at a saturated residual reverses nothing, and one that reverses
  // its changes but keeps reaching new lows makes progress.
  void
  SetChangeControl::record(const SetUpdate &update, const double residual)
  {
    history.push_back(set_signature(states));

    const bool reversing = 2 * update.n_reversed > update.n_changed;
    if (update.n_changed < best_changed || residual < best_residual)
      {
        best_changed  = std::min(best_changed, update.n_changed);
        best_residual = std::min(best_residual, residual);
        n_stalled     = 0;
      }
    else if (++n_stalled >= stagnation_window && !restricted && reversing &&
             was_reversing && restriction_allowed)
      {
        restricted = true;
        pcout << "    no progress in " << n_stalled
              << " steps (changed nodes, residual), " << update.n_reversed
              << " of " << update.n_changed
              << " changes undo earlier ones: from now on only "
                 "the nodes with the largest violations change set"
              << std::endl;
      }
    was_reversing = reversing;
  }



  unsigned int
  SetChangeControl::n_damping_steps() const
  {
    return n_damping;
  }



  // Sets without a stick node can leave a floating body 1 free to slide
  // (the system is singular; not when the normals of the active nodes hold
  // it, as the two flanks of a dovetail do). In a later Newton step that is
  // more often an iterate gone astray than a load beyond the friction limit:
  // the node nearest to sticking stays in stick, and the next step decides
  // again. An oscillating iteration whose changes are restricted loses the last
  // stick node as easily as it regains it, so the count applies only
  // before the restriction; the step limit still ends it.
  void
  SetChangeControl::keep_body_held(const bool only_where_friction_holds)
  {
    if (n_kept_stuck >= max_kept_stuck && !restricted)
      return;
    unsigned int j =
      node_nearest_to_sticking(rule, previous_weighted_slip, states);
    if (j == states.size())
      return;
    // (Every active node slips.) Held without a stick node: by its
    // Dirichlet data, or by the normals of the active nodes alone.
    const std::vector<double> velocities = support.free_slip_velocities(states);
    if (velocities.empty())
      return;
    // In step 1: the node where friction balances the load along the free
    // motion, or none (the body slides: the diagnosis follows at step 2).
    // On blocks with mu = 0.01, remeshed, step 1 lost every stick node and
    // the solve ended in "would slide" although the load along the
    // interface is 0. After step 1: the node nearest to sticking, unless
    // it is the node this update has just released from stick: keeping it
    // again repeats the sets (blocks with mu = 0.03: the same node at
    // every step, damping, then "would slide" at step 5), so the balancing
    // node is taken there. Always taking the balancing node after step 1
    // sent the stagnating case of tests/contact_stagnation to "would
    // slide" at step 20.
    const bool kept_node_just_released =
      j < states_before.size() &&
      states_before[j].status == ContactStatus::stick;
    const unsigned int balancing =
      only_where_friction_holds || kept_node_just_released ?
        node_balancing_friction(rule,
                                previous_weighted_slip,
                                states,
                                velocities) :
        states.size();
    if (balancing != states.size())
      j = balancing;
    else if (only_where_friction_holds)
      return;
    states[j].status = ContactStatus::stick;
    if (!restricted)
      ++n_kept_stuck;
    pcout << "    no stick node left: the node at (" << states[j].position[0]
          << ", " << states[j].position[1] << "), "
          << (j == balancing ? "where friction balances the load along the "
                               "interface," :
                               "nearest to sticking,")
          << " stays in stick" << std::endl;
  }
} // namespace coulomb_adapt
