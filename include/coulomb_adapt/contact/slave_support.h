#ifndef coulomb_adapt_contact_slave_support_h
#define coulomb_adapt_contact_slave_support_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * Which rigid motions of body 1 (the slave body) are held, by its own
   * Dirichlet data and by the contact sets. A body 1 without Dirichlet
   * data floats: the contact conditions alone hold it, and sets that do
   * not (no active node, no stick node against a slide along the
   * interface, or active nodes that leave a rotation free) make the Newton
   * system singular.
   *
   * The Gram matrix of body 1's supported rigid motions
   * (ElasticBody::support_gram) is computed once per load step, about the
   * mean slave node position; every test of the Newton steps reads it.
   */
  class SlaveSupport
  {
  public:
    void
    reinit(const ElasticBody                   &slave,
           const std::vector<ContactNodeState> &states);

    /** Whether body 1's Dirichlet data alone hold all its rigid motions. */
    bool
    holds_all_rigid_motions() const;

    /** Whether its Dirichlet data hold its translation along @p direction
     * (a unit vector). */
    bool
    holds_translation_along(const Tensor<1, 2> &direction) const;

    /** Whether the sets of @p states and the Dirichlet data leave a rigid
     * rotation of body 1 free (the Newton system is then singular). */
    bool
    rotation_free(const std::vector<ContactNodeState> &states) const;

    /** Whether the sets of @p states and the Dirichlet data leave body 1
     * a rigid motion that moves every active node along the contact
     * surface and no stick node (rigid_motion_left_free). */
    bool
    slip_motion_free(const std::vector<ContactNodeState> &states) const;

    /** If slip_motion_free(): the tangential velocity v_j = m(x_j) . t_j at
     * each node of the rigid motion m that the sets leave free (of unit
     * size at the active nodes; 0 at open nodes); empty otherwise. */
    std::vector<double>
    free_slip_velocities(const std::vector<ContactNodeState> &states) const;

  private:
    FullMatrix<double> gram;
    Point<2>           centre;
  };

  /** Whether the contact sets of @p states and the Dirichlet data of a
   * body (the Gram matrix @p gram of its supported rigid motions, about
   * @p gram_centre: ElasticBody::support_gram) leave a rigid motion of the
   * body free: one that moves every active node along its contact surface
   * (n . v = 0) and no stick node at all. Such a motion makes the Newton
   * system singular. The same test for either body: the constraints of a
   * node on body 2's motion are those on body 1's with the opposite sign. */
  bool
  rigid_motion_left_free(const FullMatrix<double>            &gram,
                         const Point<2>                      &gram_centre,
                         const std::vector<ContactNodeState> &states);
} // namespace coulomb_adapt

#endif
