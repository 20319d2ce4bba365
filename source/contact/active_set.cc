#include <coulomb_adapt/contact/active_set.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace coulomb_adapt
{
  double
  slip_increment(const ContactNodeState &state,
                 const double            previous_weighted_slip)
  {
    return state.slip - previous_weighted_slip / state.weight;
  }



  TrialTractions
  trial_tractions(const ContactNodeState &state,
                  const double            previous_weighted_slip,
                  const double            c)
  {
    return {state.pressure - c * state.gap,
            state.tangential_traction +
              c * slip_increment(state, previous_weighted_slip)};
  }



  double
  natural_constant(const ActiveSetRule &rule, const ContactNodeState &state)
  {
    return rule.combined_modulus / state.weight;
  }



  ContactStatus
  initial_status(const bool touching, const double friction_coefficient)
  {
    return !touching                ? ContactStatus::open :
           friction_coefficient > 0 ? ContactStatus::stick :
                                      ContactStatus::slip;
  }



  // The primal-dual active set rule: the sets the complementarity
  // functions C_n, C_t of theory.md section 2 select at the current
  // iterate. Within the convergence tolerance of the cone's edge, stick
  // and slip describe the same state (no slip increment, traction on the
  // edge): a node there keeps its status. Otherwise round-off decides, and
  // the sets can flip back and forth for ever (every slip node of the
  // previous load step sits on the edge in a load step that adds no load).
  // The tie is measured with the natural constant, as the residual is: with
  // a small scale a slip node sliding backwards by a non-negligible amount
  // would pass as a tie (doc/contact.md section 3).
  unsigned int
  update_sets(const ActiveSetRule           &rule,
              const std::vector<double>     &previous_weighted_slip,
              std::vector<ContactNodeState> &states)
  {
    const double mu        = rule.friction_coefficient;
    unsigned int n_changed = 0;
    double       p_max     = 0;
    for (const auto &s : states)
      p_max = std::max(p_max, std::abs(s.pressure));
    const double tie = rule.tolerance * p_max;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        ContactNodeState &s = states[j];
        const auto [normal, trial] =
          trial_tractions(s,
                          previous_weighted_slip[j],
                          rule.complementarity_constant[j]);
        ContactStatus status;
        int           sign = s.slip_sign;
        if (normal <= 0 || !s.facing_master)
          status = ContactStatus::open;
        else if (mu == 0)
          status = ContactStatus::slip;
        else if (s.held_tangentially)
          status = ContactStatus::stick; // the support holds it
        else
          {
            const auto natural = trial_tractions(s,
                                                 previous_weighted_slip[j],
                                                 natural_constant(rule, s));
            const bool at_edge = std::abs(std::abs(natural.tangential) -
                                          mu * natural.normal) <= tie &&
                                 s.status != ContactStatus::open;
            if (at_edge ? s.status == ContactStatus::stick :
                          std::abs(trial) < mu * normal)
              status = ContactStatus::stick;
            else
              {
                status = ContactStatus::slip;
                sign   = trial >= 0 ? 1 : -1;
              }
          }
        if (status != s.status ||
            (status == ContactStatus::slip && mu > 0 && sign != s.slip_sign))
          ++n_changed;
        s.status    = status;
        s.slip_sign = sign;
      }
    return n_changed;
  }



  double
  largest_pressure(const std::vector<ContactNodeState> &states)
  {
    double p = 0;
    for (const auto &s : states)
      p = std::max(p, std::abs(s.pressure));
    return p == 0 ? 1. : p;
  }



  // How far a node is from its contact conditions: |C_n| / p and
  // |C_t| / p^2, p the largest pressure, evaluated with the natural
  // constant whatever scale drives the set update.
  double
  node_residual(const ActiveSetRule    &rule,
                const ContactNodeState &s,
                const double            previous_weighted_slip,
                const double            p)
  {
    if (!s.facing_master)
      return 0; // no contact possible: lambda_j = 0 by construction
    const double mu = rule.friction_coefficient;
    const auto [normal, trial] =
      trial_tractions(s, previous_weighted_slip, natural_constant(rule, s));
    const double C_n = s.pressure - std::max(0., normal);
    // C_t is homogeneous of degree 2 in (lambda, c u): scale it by p
    // and by the size of its trial traction.
    // (At a node held tangentially the Dirichlet condition replaces the
    // tangential one: lambda_t = 0 by construction.)
    const double C_t = s.held_tangentially ? 0. :
                       (mu == 0)           ? s.tangential_traction * p :
                                   std::max(mu * normal, std::abs(trial)) *
                                       s.tangential_traction -
                                     mu * std::max(0., normal) * trial;
    return std::max(std::abs(C_n) / p,
                    std::abs(C_t) / (p * std::max(p, std::abs(trial))));
  }



  double
  complementarity_residual(const ActiveSetRule       &rule,
                           const std::vector<double> &previous_weighted_slip,
                           const std::vector<ContactNodeState> &states)
  {
    const double p        = largest_pressure(states);
    double       residual = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      residual =
        std::max(residual,
                 node_residual(rule, states[j], previous_weighted_slip[j], p));
    return residual;
  }



  // Globalisation of the rule when it makes no progress: the rule moves
  // every node that violates its conditions at once, and where the
  // multipliers are only weakly determined (a stiff, nearly incompressible
  // body 1 on a coarse soft body 2) the nodes' changes undo each other's.
  // Moving only the worst nodes lets the others follow the new sets'
  // solution. The converged sets do not depend on it: they must pass the
  // full rule unchanged.
  unsigned int
  restrict_set_changes(const ActiveSetRule       &rule,
                       const std::vector<double> &previous_weighted_slip,
                       const std::vector<ContactNodeState> &before,
                       const double                         fraction,
                       std::vector<ContactNodeState>       &states)
  {
    const double p       = largest_pressure(states);
    const auto   changed = [&](const unsigned int j) {
      return states[j].status != before[j].status ||
             (states[j].status == ContactStatus::slip &&
              states[j].slip_sign != before[j].slip_sign);
    };
    std::vector<double> r(states.size(), 0.);
    double              largest = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      if (changed(j))
        largest = std::max(
          largest,
          r[j] = node_residual(rule, states[j], previous_weighted_slip[j], p));
    unsigned int n_kept = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      if (changed(j))
        {
          if (r[j] >= fraction * largest)
            ++n_kept;
          else
            {
              states[j].status    = before[j].status;
              states[j].slip_sign = before[j].slip_sign;
            }
        }
    return n_kept;
  }



  // Nearest to sticking: smallest |trial| / (mu normal).
  unsigned int
  node_nearest_to_sticking(const ActiveSetRule       &rule,
                           const std::vector<double> &previous_weighted_slip,
                           const std::vector<ContactNodeState> &states)
  {
    const double       mu   = rule.friction_coefficient;
    const unsigned int none = states.size();
    if (mu == 0)
      return none;
    unsigned int best  = none;
    double       ratio = std::numeric_limits<double>::max();
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        const auto &s = states[j];
        if (s.status == ContactStatus::stick)
          return none;
        if (s.status == ContactStatus::open)
          continue;
        const auto [normal, trial] =
          trial_tractions(s,
                          previous_weighted_slip[j],
                          rule.complementarity_constant[j]);
        if (normal > 0 && std::abs(trial) / (mu * normal) < ratio)
          ratio = std::abs(trial) / (mu * normal), best = j;
      }
    return best;
  }



  unsigned int
  node_balancing_friction(const ActiveSetRule       &rule,
                          const std::vector<double> &previous_weighted_slip,
                          const std::vector<ContactNodeState> &states,
                          const std::vector<double>           &velocities)
  {
    const double       mu   = rule.friction_coefficient;
    const unsigned int none = states.size();
    if (mu == 0 || velocities.size() != states.size())
      return none;
    struct Flip
    {
      double       at;
      double       jump;
      unsigned int node;
    };
    std::vector<Flip> flips;
    double            load = 0, lowest = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        const ContactNodeState &s = states[j];
        if (s.status == ContactStatus::open)
          continue;
        const double v = velocities[j];
        load += s.weight * v * s.tangential_traction;
        const auto [normal, trial] =
          trial_tractions(s,
                          previous_weighted_slip[j],
                          rule.complementarity_constant[j]);
        const double c = rule.complementarity_constant[j];
        if (normal <= 0 || v == 0 || c <= 0)
          continue;
        const double force = s.weight * std::abs(v) * mu * normal;
        lowest -= force;
        flips.push_back({-trial / (c * v), 2 * force, j});
      }
    std::sort(flips.begin(), flips.end(), [](const Flip &a, const Flip &b) {
      return a.at < b.at;
    });
    double friction = lowest;
    for (const Flip &flip : flips)
      {
        if (friction <= load && load <= friction + flip.jump)
          return flip.node;
        friction += flip.jump;
      }
    return none;
  }



  std::string
  set_signature(const std::vector<ContactNodeState> &states)
  {
    std::string signature;
    for (const auto &s : states)
      signature += s.status == ContactStatus::open  ? 'o' :
                   s.status == ContactStatus::stick ? 't' :
                   s.slip_sign > 0                  ? '+' :
                                                      '-';
    return signature;
  }
} // namespace coulomb_adapt
