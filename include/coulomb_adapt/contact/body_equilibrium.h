#ifndef coulomb_adapt_contact_body_equilibrium_h
#define coulomb_adapt_contact_body_equilibrium_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/mortar_interface.h>

#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The force balance of one body in a converged contact solution: along
   * each rigid motion that its Dirichlet data leave free, the applied
   * loads and the contact tractions must balance (the reactions of
   * Dirichlet data balance the rest). The Newton iteration's residual says
   * that the contact conditions hold node by node; it does not see a
   * singular system whose solution satisfies them with forces that do not
   * balance the load (a block beside the other one, pushed along the
   * interface; a block tipping over an edge on one active node).
   *
   * Resultants are z^T f and z^T c for the free rigid modes z (x- and
   * y-translation, rotation about the body's mean contact node, divided by
   * the interface's extent so that all three are forces), f the assembled
   * load and c the mortar contact forces: -D lambda at the slave nodes of
   * body 1, M^T lambda at the master nodes of body 2.
   */
  struct BodyEquilibrium
  {
    /** Number of free rigid motions (0 ... 3) that were checked. */
    unsigned int n_free_modes = 0;
    /** Resultant of the applied loads and of the contact forces (N/mm),
     * and the moment of both about @p centre (N), over the free modes. */
    Tensor<1, 2> load_force, contact_force;
    double       load_moment = 0, contact_moment = 0;
    Point<2>     centre;
    /** Largest |z^T (f + c)| over the free unit modes (N/mm). */
    double imbalance = 0;
    /** Round-off bound of that sum: (terms per row + 2 + sqrt(rows)) eps
     * times the sum of the magnitudes of the terms of z^T (f - K u) and
     * z^T c, plus the linear solver's tolerance on |f|. */
    double round_off = 0;
    /** The scale of the forces that balance: sum |z_i f_i| + sum |z c|. */
    double force_scale = 0;
    /** Whether the imbalance is mostly a moment (the body tips) rather
     * than a force (it slides). */
    bool tips = false;

    /** Balanced to round-off, and the round-off itself below the forces
     * (@p force_scale), without which the balance says nothing: a
     * regular system's round-off is the number of terms times eps times
     * its condition number times the forces, a singular one's (a body the
     * contact sets do not hold) the number of terms times the forces or
     * more. */
    bool
    balanced() const;
  };

  /** The balance of body 1 (@p slave = true, contact forces -D lambda at
   * its slave nodes) or body 2 (M^T lambda at its master nodes) for the
   * multipliers of @p states. Collective over the body's communicator;
   * every rank gets the same result. @p linear_tolerance: the relative
   * tolerance on |f| of the last linear solve (0 for a direct solve). */
  BodyEquilibrium
  body_equilibrium(const ElasticBody                   &body,
                   const bool                           slave,
                   const MortarInterface               &mortar,
                   const std::vector<ContactNodeState> &states,
                   const double                         linear_tolerance);

  /** The diagnosis of an unbalanced body: its loads, contact force and
   * imbalance, and what that means (it slides or tips: no static
   * equilibrium, or the contact sets do not hold it). */
  std::string
  equilibrium_message(const std::string &body_label, const BodyEquilibrium &e);
} // namespace coulomb_adapt

#endif
