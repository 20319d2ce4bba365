#include <coulomb_adapt/contact/first_step_rule.h>

#include <algorithm>
#include <utility>

namespace coulomb_adapt
{
  // The rule of the first Newton step from the initial gap
  // (first_step_rule.h); ContactSolver::iterate() applies it.
  namespace
  {
    // The nodes that the first step's rule closed (open before, @p before)
    // but that penetrate less deeply than the fraction of the deepest
    // start open again; @p update is corrected. Returns their number.
    unsigned int
    open_shallow_penetration(const std::vector<ContactStatus> &before,
                             std::vector<ContactNodeState>    &states,
                             SetChangeControl::SetUpdate      &update)
    {
      const auto newly_closed = [&](const unsigned int j) {
        return before[j] == ContactStatus::open &&
               states[j].status != ContactStatus::open;
      };
      double deepest = 0;
      for (unsigned int j = 0; j < states.size(); ++j)
        if (newly_closed(j))
          deepest = std::min(deepest, states[j].gap);
      unsigned int n_opened = 0;
      for (unsigned int j = 0; j < states.size(); ++j)
        if (newly_closed(j) &&
            states[j].gap > first_step_penetration_fraction * deepest)
          {
            states[j].status = ContactStatus::open;
            ++n_opened;
          }
      std::vector<unsigned int> changed;
      for (const unsigned int j : update.changed)
        if (states[j].status != before[j])
          changed.push_back(j);
      update.changed = changed;
      update.n_moved = changed.size();
      return n_opened;
    }
  } // namespace



  // open_shallow_penetration(), unless that leaves body 1 free to turn
  // where the rule's sets hold it.
  unsigned int
  close_deepest_penetration_only(const std::vector<ContactStatus> &before,
                                 const SlaveSupport               &support,
                                 std::vector<ContactNodeState>    &states,
                                 SetChangeControl::SetUpdate      &update)
  {
    auto               limited        = states;
    auto               limited_update = update;
    const unsigned int n =
      open_shallow_penetration(before, limited, limited_update);
    if (n == 0 ||
        (support.rotation_free(limited) && !support.rotation_free(states)))
      return 0;
    states = std::move(limited);
    update = std::move(limited_update);
    return n;
  }
} // namespace coulomb_adapt
