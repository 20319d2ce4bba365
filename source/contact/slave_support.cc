#include <deal.II/base/symmetric_tensor.h>

#include <coulomb_adapt/bodies/rigid_motion_gram.h>
#include <coulomb_adapt/contact/slave_support.h>

#include <algorithm>

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



  namespace
  {
    // The Gram matrix @p gram of the supported rigid motions (rotation
    // about @p gram_centre) with the rows of the active nodes added: n . u
    // at every active node, t . u at stick nodes, all taken about the
    // active nodes' centroid, which is returned in @p active_centre (left
    // unchanged without active nodes).
    FullMatrix<double>
    gram_with_active_nodes(const FullMatrix<double>            &gram,
                           const Point<2>                      &gram_centre,
                           const std::vector<ContactNodeState> &states,
                           Point<2>                            &active_centre)
    {
      Point<2>     sum;
      unsigned int n_active = 0;
      for (const auto &s : states)
        if (s.status != ContactStatus::open)
          {
            sum += s.position;
            ++n_active;
          }
      if (n_active > 0)
        active_centre = sum / static_cast<double>(n_active);
      FullMatrix<double> constrained =
        move_rotation_centre(gram, active_centre - gram_centre);
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
      return constrained;
    }



    // gram_with_active_nodes on one scale for all three modes: the
    // rotation divided by the active nodes' extent L about their centroid
    // (a rotation of unit size at the farthest active node), so that its
    // eigenvalues compare with the translations'. L = 0 (a single active
    // node, or none) leaves the rotation unscaled.
    struct ScaledActiveGram
    {
      FullMatrix<double>    unscaled;
      SymmetricTensor<2, 3> matrix;
      Point<2>              active_centre;
      double                extent = 0;
    };

    ScaledActiveGram
    scaled_gram_with_active_nodes(const FullMatrix<double> &gram,
                                  const Point<2>           &gram_centre,
                                  const std::vector<ContactNodeState> &states)
    {
      ScaledActiveGram result;
      result.active_centre = gram_centre;
      result.unscaled =
        gram_with_active_nodes(gram, gram_centre, states, result.active_centre);
      for (const auto &s : states)
        if (s.status != ContactStatus::open)
          result.extent =
            std::max(result.extent, result.active_centre.distance(s.position));
      const double scale[3] = {1.,
                               1.,
                               result.extent > 0 ? 1. / result.extent : 1.};
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = a; b < 3; ++b)
          result.matrix[a][b] = scale[a] * result.unscaled(a, b) * scale[b];
      return result;
    }
  } // namespace



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
    Point<2> active_centre = centre;
    return !coulomb_adapt::holds_all_rigid_motions(
      gram_with_active_nodes(gram, centre, states, active_centre));
  }



  bool
  SlaveSupport::slip_motion_free(
    const std::vector<ContactNodeState> &states) const
  {
    return rigid_motion_left_free(gram, centre, states);
  }



  std::vector<double>
  SlaveSupport::free_slip_velocities(
    const std::vector<ContactNodeState> &states) const
  {
    if (!slip_motion_free(states))
      return {};
    const ScaledActiveGram g =
      scaled_gram_with_active_nodes(gram, centre, states);
    const Point<2> &c = g.active_centre;
    // The eigenvector of the smallest eigenvalue, back from the scaled
    // rotation to (u_x, u_y, theta).
    const double        rotation_scale = g.extent > 0 ? 1. / g.extent : 1.;
    const Tensor<1, 3>  y              = eigenvectors(g.matrix)[2].second;
    std::vector<double> velocities(states.size(), 0.);
    for (unsigned int j = 0; j < states.size(); ++j)
      if (states[j].status != ContactStatus::open)
        {
          const Tensor<1, 2> r = states[j].position - c;
          const Tensor<1, 2> m({y[0] - y[2] * rotation_scale * r[1],
                                y[1] + y[2] * rotation_scale * r[0]});
          velocities[j] = m * states[j].tangent;
        }
    return velocities;
  }



  // The rows of the active nodes as in rotation_free, but the test whether
  // they hold every rigid motion compares all three modes on one scale:
  // the rotation about the active nodes' centroid divided by their extent
  // L (a motion of at most unit size at the nodes), and the smallest
  // eigenvalue against the trace. rotation_free's test, relative to the
  // rotation's own diagonal entry, takes the round-off of normals that
  // all pass through one point (a circle's) for a held rotation; here it
  // stays round-off against the trace, while the two flanks of a wedge
  // hold every motion by a clear margin (doc/contact.md).
  bool
  rigid_motion_left_free(const FullMatrix<double>            &gram,
                         const Point<2>                      &gram_centre,
                         const std::vector<ContactNodeState> &states)
  {
    if (std::none_of(states.begin(), states.end(), [](const auto &s) {
          return s.status != ContactStatus::open;
        }))
      return !coulomb_adapt::holds_all_rigid_motions(gram);
    const ScaledActiveGram g =
      scaled_gram_with_active_nodes(gram, gram_centre, states);
    // A single active node (L = 0) holds no rotation: only the Dirichlet
    // data can.
    if (g.extent == 0)
      return !coulomb_adapt::holds_all_rigid_motions(g.unscaled);
    const auto values = eigenvalues(g.matrix);
    return values[2] <= 1e-10 * trace(g.matrix);
  }
} // namespace coulomb_adapt
