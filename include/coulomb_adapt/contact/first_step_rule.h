#ifndef coulomb_adapt_contact_first_step_rule_h
#define coulomb_adapt_contact_first_step_rule_h

#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/set_change_control.h>
#include <coulomb_adapt/contact/slave_support.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * The first Newton step of a contact solve started from the initial gap
   * (ContactSolver::iterate): of the nodes its solve pushes into
   * penetration, only those within this fraction of the deepest
   * penetration are closed. Closing all of them over-estimates the
   * contact zone (hertz: 1.7-2 times its nodes), which the following
   * steps then open again at its edges, one node per side and step;
   * closing the deepest ones under-estimates it, and the next solve's
   * penetration closes the rest in one step (hertz Q1 at 3,500 DoFs: 4
   * Newton steps instead of 7; benchmarks/contact/README.md, "Newton steps
   * on every scene").
   */
  constexpr double first_step_penetration_fraction = 0.95;

  /**
   * The first step's rule applied to the sets that the active set rule
   * chose (@p states, with its @p update) from the statuses @p before
   * the step: the newly closed nodes that penetrate less deeply than
   * first_step_penetration_fraction times the deepest open again, and
   * @p update is corrected. Not applied (returns 0) if that would leave
   * body 1 free to turn where the rule's sets hold it (@p support).
   * Returns the number of nodes left open.
   */
  unsigned int
  close_deepest_penetration_only(const std::vector<ContactStatus> &before,
                                 const SlaveSupport               &support,
                                 std::vector<ContactNodeState>    &states,
                                 SetChangeControl::SetUpdate      &update);
} // namespace coulomb_adapt

#endif
