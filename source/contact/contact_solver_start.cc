#include <deal.II/base/timer.h>

#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/contact/body_equilibrium.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/contact/eliminated_contact_system.h>
#include <coulomb_adapt/contact/newton_diagnostics.h>
#include <coulomb_adapt/contact/row_replacing_contact_system.h>
#include <coulomb_adapt/contact/set_change_control.h>

#include <algorithm>
#include <array>
#include <limits>

namespace coulomb_adapt
{
  // Where the Newton iteration of a contact solve starts: the sets from
  // the initial gap, or taken over from the solve on another mesh (warm
  // start), and the slave nodes' states they live in.

  // The states (sets and slip history) persist from one load step to the
  // next on the same mesh.
  void
  ContactSolver::setup_states()
  {
    const auto        &nodes      = mortar.slave_nodes();
    const auto        &D          = mortar.slave_weights();
    const unsigned int n_slave    = nodes.size();
    const bool         first_step = states.size() != n_slave;
    if (first_step)
      {
        states.assign(n_slave, {});
        previous_weighted_slip.assign(n_slave, 0.);
      }
    for (unsigned int j = 0; j < n_slave; ++j)
      {
        states[j].position          = nodes[j].position;
        states[j].normal            = nodes[j].normal;
        states[j].tangent           = nodes[j].tangent;
        states[j].weight            = D[j];
        states[j].held_tangentially = condensation.fixed_component[j] >= 0;
      }
    if (first_step)
      load_step_start.clear();
    else
      load_step_start = states;
    support.reinit(slave, states);
    master_gram = master.support_gram(Point<2>());
    if (first_step)
      initialize_sets();
    // A later load step starts from the sets of the step before, unless
    // the same load step on a coarser mesh gave its sets (nested iteration
    // along a load path): only the sets are taken over, the history (the
    // tangential jump at the end of the step before) is this mesh's own.
    if (!warm_start_states.empty())
      transfer_warm_start_sets();
  }



  // Nodes that touch in the initial configuration start active: stuck if
  // there is friction, which holds a floating body 1 in the first step.
  void
  ContactSolver::initialize_sets()
  {
    const auto &gaps = mortar.weighted_initial_gaps();
    const auto &D    = mortar.slave_weights();
    // The interface's extent: the same on every rank.
    double size = 0;
    for (const auto &s : states)
      size = std::max(size, s.position.distance(states.front().position));
    // A floating body 1 that does not touch yet would start from the
    // open set, where nothing holds it and the first Newton system is
    // singular (before: "nothing holds it (is it loaded towards body
    // 2?)" for any initial gap, even 0.001 mm, of a body loaded towards
    // body 2). It starts closed where the gap is smallest instead: those
    // nodes are the first to touch, and the set rule opens them again if
    // the load pulls the body away.
    double closest = std::numeric_limits<double>::max();
    for (unsigned int j = 0; j < states.size(); ++j)
      if (mortar.is_covered(j))
        closest = std::min(closest, gaps[j] / D[j]);
    const double closed_below = support.holds_all_rigid_motions() ?
                                  1e-10 * size :
                                  std::max(closest, 0.) + 1e-10 * size;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        const bool touching =
          mortar.is_covered(j) && gaps[j] / D[j] <= closed_below;
        states[j].status    = initial_status(touching, mu);
        states[j].slip_sign = 1;
      }
  }



  // The continuation predictor of a load path (predict_next_load_step):
  // the state at the end of the last load step moved on by the ratio
  // times its increments in that step, and the sets the active set rule
  // reads off it. A stick node whose tangential traction grows out of the
  // cone over the next increment starts slipping, so the slip front
  // starts where the load moves it instead of where it was, which the
  // Newton iteration would otherwise move a band of nodes per step.
  unsigned int
  ContactSolver::predict_sets()
  {
    std::vector<ContactNodeState> predicted = states;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        const Increment &d = last_increments[j];
        predicted[j].pressure += predictor_ratio * d.pressure;
        predicted[j].tangential_traction +=
          predictor_ratio * d.tangential_traction;
        predicted[j].gap += predictor_ratio * d.gap;
        predicted[j].slip += predictor_ratio * d.slip;
      }
    const unsigned int n_changed =
      update_sets(rule, previous_weighted_slip, predicted);
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        states[j].status    = predicted[j].status;
        states[j].slip_sign = predicted[j].slip_sign;
      }
    return n_changed;
  }



  // Nearest previous node by position: the interface is a curve, and the
  // meshes of two cycles resolve it differently. A previous mesh with at
  // most two active nodes gives their closed set only, each closed node
  // stuck as from the initial gap: nearest-node transfer would copy one
  // node's stick or slip onto a stretch of the zone (dovetail's .geo at 4x
  // its mesh size: one node per flank, one stuck, one slipping; the 2x
  // mesh then cycled, 5 Newton steps instead of 2).
  void
  ContactSolver::transfer_warm_start_sets()
  {
    std::vector<ContactNodeState> transferred = states;
    unsigned int                  n_active    = 0;
    const bool                    closed_set_only =
      mu > 0 && std::count_if(warm_start_states.begin(),
                              warm_start_states.end(),
                              [](const ContactNodeState &s) {
                                return s.status != ContactStatus::open;
                              }) <= 2;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        if (!mortar.is_covered(j))
          continue;
        const ContactNodeState *nearest = nullptr;
        double                  best    = std::numeric_limits<double>::max();
        for (const auto &p : warm_start_states)
          {
            const double d = p.position.distance_square(states[j].position);
            if (d < best)
              best = d, nearest = &p;
          }
        transferred[j].status    = nearest->status;
        transferred[j].slip_sign = nearest->slip_sign;
        if (closed_set_only && transferred[j].status == ContactStatus::slip)
          transferred[j].status = ContactStatus::stick;
        if (mu == 0 && transferred[j].status == ContactStatus::stick)
          transferred[j].status = ContactStatus::slip;
        if (mu > 0 && states[j].held_tangentially &&
            transferred[j].status == ContactStatus::slip)
          transferred[j].status = ContactStatus::stick;
        n_active += (transferred[j].status != ContactStatus::open);
      }
    if (n_active > 0 || support.holds_all_rigid_motions())
      states = transferred;
  }



  void
  ContactSolver::warm_start_from(const std::vector<ContactNodeState> &previous)
  {
    warm_start_states = previous;
  }
} // namespace coulomb_adapt
