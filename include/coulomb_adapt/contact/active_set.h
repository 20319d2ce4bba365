#ifndef coulomb_adapt_contact_active_set_h
#define coulomb_adapt_contact_active_set_h

#include <coulomb_adapt/contact/contact_state.h>

#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The constants of the primal-dual active set rule (theory.md section
   * 2.3). The complementarity functions
   *
   *   C_n = lambda_n - max(0, lambda_n - c g),
   *   C_t = max(mu (lambda_n - c g), |lambda_t + c dW_t|) lambda_t
   *         - mu max(0, lambda_n - c g) (lambda_t + c dW_t)
   *
   * vanish exactly when the contact conditions hold, for every c > 0; the
   * rule reads the sets off their arguments. The constants c_j drive the
   * set update (Contact/Complementarity scale times E_c / D_jj, reduced
   * when the sets cycle); the residual is always measured with the
   * natural constants E_c / D_jj, so that the tolerance means the same
   * whatever the scale.
   *
   * The functions below are pure: they read the node states of the
   * current iterate, the weighted slip at the end of the previous load
   * step and these constants, and change only the sets they are given.
   */
  struct ActiveSetRule
  {
    double friction_coefficient = 0;
    /** Contact/Tolerance: also the width of the cone's edge within which
     * stick and slip are the same state. */
    double tolerance = 0;
    /** E_c = E1 E2 / (E1 + E2). */
    double combined_modulus = 0;
    /** c_j = c_n = c_t of each slave node. */
    std::vector<double> complementarity_constant;
  };

  /** The arguments of the complementarity functions at a node for the
   * constant c: lambda_n - c g and the trial traction lambda_t + c dW_t. */
  struct TrialTractions
  {
    double normal;
    double tangential;
  };

  /** Tangential slip of a node in the current load step (mm). */
  double
  slip_increment(const ContactNodeState &state,
                 const double            previous_weighted_slip);

  TrialTractions
  trial_tractions(const ContactNodeState &state,
                  const double            previous_weighted_slip,
                  const double            c);

  /** The natural constant E_c / D_jj of a node, independent of
   * 'Contact/Complementarity scale'. */
  double
  natural_constant(const ActiveSetRule &rule, const ContactNodeState &state);

  /** The status a node starts from: touching nodes are active, stuck if
   * there is friction. */
  ContactStatus
  initial_status(const bool touching, const double friction_coefficient);

  /** Apply the active set rule to every node; returns the number of nodes
   * whose status (or slip direction) changed. */
  unsigned int
  update_sets(const ActiveSetRule           &rule,
              const std::vector<double>     &previous_weighted_slip,
              std::vector<ContactNodeState> &states);

  /** The largest contact pressure (1 if there is none). */
  double
  largest_pressure(const std::vector<ContactNodeState> &states);

  /** A node's term of the complementarity residual, normalised by the
   * largest pressure @p p. */
  double
  node_residual(const ActiveSetRule    &rule,
                const ContactNodeState &state,
                const double            previous_weighted_slip,
                const double            p);

  /** max_j of node_residual(): zero exactly when the contact conditions
   * hold. */
  double
  complementarity_residual(const ActiveSetRule       &rule,
                           const std::vector<double> &previous_weighted_slip,
                           const std::vector<ContactNodeState> &states);

  /** Restricted set update: of the nodes whose sets changed from
   * @p before, only those whose residual is at least @p fraction of the
   * largest keep the change; the others return to @p before. Returns the
   * number of nodes that keep their change. */
  unsigned int
  restrict_set_changes(const ActiveSetRule       &rule,
                       const std::vector<double> &previous_weighted_slip,
                       const std::vector<ContactNodeState> &before,
                       const double                         fraction,
                       std::vector<ContactNodeState>       &states);

  /** With friction and no stick node in the sets: the active node whose
   * trial traction lies deepest inside the Coulomb cone. states.size() if
   * there is a stick node, no friction or no such node. */
  unsigned int
  node_nearest_to_sticking(const ActiveSetRule       &rule,
                           const std::vector<double> &previous_weighted_slip,
                           const std::vector<ContactNodeState> &states);

  /**
   * With friction, every active node slipping and a rigid motion of body 1
   * left free (tangential velocity @p velocities at the nodes,
   * SlaveSupport::free_slip_velocities()): the node that sticks in the
   * solution. Moving the body by r along the motion shifts each node's
   * trial traction by c_j v_j r, so each slip direction flips at its own
   * r; the friction the active nodes exert along the motion, F(r) = sum_j
   * D_j v_j mu lambda_n,j sign(trial_j + c_j v_j r), grows by
   * 2 D_j |v_j| mu lambda_n,j at each flip, while the load along the
   * motion is what the current tractions exert, F* = sum_j D_j v_j
   * lambda_t,j (every Newton iterate is in equilibrium). The node whose
   * flip takes F past F* sticks. states.size() if F* is beyond what
   * friction can exert (the body slides), or without such nodes.
   */
  unsigned int
  node_balancing_friction(const ActiveSetRule       &rule,
                          const std::vector<double> &previous_weighted_slip,
                          const std::vector<ContactNodeState> &states,
                          const std::vector<double>           &velocities);

  /** The sets as a string, one character per node: 'o' open, 't' stick,
   * '+' and '-' slip in either direction. */
  std::string
  set_signature(const std::vector<ContactNodeState> &states);
} // namespace coulomb_adapt

#endif
