#ifndef coulomb_adapt_contact_set_change_control_h
#define coulomb_adapt_contact_set_change_control_h

#include <deal.II/base/conditional_ostream.h>

#include <coulomb_adapt/contact/active_set.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/slave_support.h>

#include <optional>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Globalisation of the primal-dual active set iteration within one load
   * step (doc/contact.md section 3). The full rule (update_sets) moves
   * every node that violates its conditions at once; two failure modes
   * follow, and each has its remedy here:
   *
   * - a cycle (the sets repeat those of an earlier step): the constants
   *   c_n = c_t are reduced ten-fold, at most four times, which makes the
   *   rule move fewer nodes per step (the solution does not depend on c);
   * - stagnation without a cycle: for several steps neither the number of
   *   changed nodes nor the residual reaches a new low, and most changes
   *   return nodes to a status they held earlier (they undo each other).
   *   Where friction alone holds body 1 tangentially, whose tangential
   *   equilibrium couples every stick/slip change to all others, the rest
   *   of the load step moves only the nodes with the largest violations
   *   (restrict_set_changes).
   *
   * A third guard keeps a floating body 1 held: sets after the first step
   * that leave no stick node keep the node nearest to sticking in stick,
   * a few times per load step (every time once the changes are
   * restricted).
   *
   * Convergence is always tested with the full rule, so the converged sets
   * are the ones the rule accepts, whatever happened on the way.
   */
  class SetChangeControl
  {
  public:
    /** Acts on @p states and on the constants of @p rule (damping) during
     * one load step. */
    SetChangeControl(ActiveSetRule                 &rule,
                     std::vector<ContactNodeState> &states,
                     const std::vector<double>     &previous_weighted_slip,
                     const SlaveSupport            &support,
                     const bool                     restriction_allowed,
                     const ConditionalOStream      &pcout);

    /** Newton step @p k is about to solve with the current sets. */
    void
    begin_step(const unsigned int k);

    /** What a set update did. */
    struct SetUpdate
    {
      /** Nodes the full rule changes. */
      unsigned int n_changed = 0;
      /** Of those, the nodes that keep their change (restricted). */
      unsigned int n_moved = 0;
      /** Nodes the full rule sends back to a status held before. */
      unsigned int n_reversed = 0;
      /** Nodes whose sets differ from those of the step's solve. */
      std::vector<unsigned int> changed;
    };

    /** Apply the rule to the iterate of Newton step @p k (the states'
     * tractions, gaps and slips evaluated): the full rule, restricted once
     * the iteration stagnates, and body 1 kept held. */
    SetUpdate
    update_sets(const unsigned int k);

    /** The step whose sets the current ones repeat (other than the
     * previous one), if any: the iteration cycles. */
    std::optional<unsigned int>
    repeated_step() const;

    /** Break the cycle that repeats step @p repeated, found after Newton
     * step @p k, by damping: c reduced ten-fold and the sets re-evaluated.
     * Returns false (nothing done) when c was reduced as often as allowed
     * already. */
    bool
    damp(const unsigned int k, const unsigned int repeated);

    /** Record the new sets of a step that changed them (not a cycle), and
     * watch for stagnation. */
    void
    record(const SetUpdate &update, const double residual);

    /** How often c was reduced in this load step. */
    unsigned int
    n_damping_steps() const;

  private:
    /** With friction and sets that leave no stick node and nothing else
     * holding body 1 tangentially: with @p only_where_friction_holds (step
     * 1) the node where friction balances the load along the free motion
     * (node_balancing_friction()) stays in stick, if there is one;
     * otherwise the active node nearest to sticking. */
    void
    keep_body_held(const bool only_where_friction_holds);

    ActiveSetRule                 &rule;
    std::vector<ContactNodeState> &states;
    const std::vector<double>     &previous_weighted_slip;
    const SlaveSupport            &support;
    const bool                     restriction_allowed;
    const ConditionalOStream      &pcout;

    /** The sets of the steps since the start or the last damping. */
    std::vector<std::string> history;
    /** The states as the last step solved with them. */
    std::vector<ContactNodeState> states_before;
    /** For each node, the statuses (bits: open, stick, slip +, slip -) of
     * the sets that Newton steps 2, 3, ... solved with; the initial or
     * predicted sets of step 1 do not count. */
    std::vector<unsigned char> statuses_held;

    unsigned int n_damping  = 0;
    bool         restricted = false;
    unsigned int best_changed;
    double       best_residual;
    unsigned int n_stalled     = 0;
    bool         was_reversing = false;
    unsigned int n_kept_stuck  = 0;

    static constexpr unsigned int max_damping_steps   = 4;
    static constexpr unsigned int stagnation_window   = 4;
    static constexpr double       restricted_fraction = 0.5;
    static constexpr unsigned int max_kept_stuck      = 4;
  };
} // namespace coulomb_adapt

#endif
