#include <coulomb_adapt/bodies/rigid_motion_gram.h>
#include <coulomb_adapt/contact/slave_support.h>

namespace coulomb_adapt
{
  void
  SlaveSupport::reinit(const ElasticBody                   &slave,
                       const std::vector<ContactNodeState> &states)
  {
    centre = Point<2>();
    for (const auto &s : states)
      centre += s.position / static_cast<double>(states.size());
    gram = slave.support_gram(centre);
  }



  bool
  SlaveSupport::holds_all_rigid_motions() const
  {
    return coulomb_adapt::holds_all_rigid_motions(gram);
  }



  bool
  SlaveSupport::holds_translation_along(const Tensor<1, 2> &direction) const
  {
    return coulomb_adapt::holds_translation_along(gram, direction);
  }



  // Translations held, but perhaps not the rotation: a body resting on one
  // active node (a disc on a mesh coarser than its contact zone, or the
  // first step from the initial gap) or on nodes whose normals meet in one
  // point can turn about it. Each active node fixes n . u at its position,
  // a stick node t . u too: rows added to the Gram matrix of body 1's
  // supported rigid motions. They are taken about the centroid of the
  // active nodes: about a centre far away, the rows of a small contact
  // zone would look like those of a single point.
  bool
  SlaveSupport::rotation_free(const std::vector<ContactNodeState> &states) const
  {
    Point<2>     active_centre;
    unsigned int n_active = 0;
    for (const auto &s : states)
      if (s.status != ContactStatus::open)
        {
          active_centre += s.position;
          ++n_active;
        }
    active_centre =
      (n_active > 0) ? active_centre / static_cast<double>(n_active) : centre;
    FullMatrix<double> constrained =
      move_rotation_centre(gram, active_centre - centre);
    for (const auto &s : states)
      if (s.status != ContactStatus::open)
        {
          add_rigid_motion_constraint(constrained,
                                      s.normal,
                                      s.position,
                                      active_centre);
          if (s.status == ContactStatus::stick)
            add_rigid_motion_constraint(constrained,
                                        s.tangent,
                                        s.position,
                                        active_centre);
        }
    return !coulomb_adapt::holds_all_rigid_motions(constrained);
  }
} // namespace coulomb_adapt
