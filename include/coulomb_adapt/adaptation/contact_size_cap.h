#ifndef coulomb_adapt_adaptation_contact_size_cap_h
#define coulomb_adapt_adaptation_contact_size_cap_h

#include <coulomb_adapt/adaptation/size_field.h>
#include <coulomb_adapt/bodies/elastic_body.h>

#include <array>
#include <vector>

namespace coulomb_adapt
{
  /** The master's facets along a curved contact surface are at most this
   * many times as long as the slave's facets they face. */
  constexpr double master_to_slave_size_ratio = 1.;

  /** Away from the capped contact surface the size may grow by at most
   * this much per unit distance (dh/dx), so that the cells between the
   * fine contact surface and the coarse interior are well shaped. */
  constexpr double contact_size_grading = 0.3;

  /**
   * Limit the master body's size field (body 1, @p fields[1]) along a
   * curved contact surface to master_to_slave_size_ratio times the slave's
   * (body 0, @p fields[0]) where the slave faces it, graded into the body
   * by contact_size_grading. With P1 the contact surfaces are polygons: the
   * mortar measures the initial gap between the true curves, but the
   * master's displacement, the coupling matrix and the normals live on the
   * master's chords, whose kinks (a change of direction h / R at each
   * master vertex) the slave nodes feel as pressure oscillations when the
   * master's chords are much longer than the slave's: an estimator that
   * sees no error in a uniformly stressed master coarsens it there. A
   * straight master surface has no kinks and its field is not changed;
   * the remesher calls this for P1 only (P2's faces follow the curve,
   * doc/scenes.md).
   *
   * Collective over the bodies' communicator; @p fields[b] lives on rank
   * @p root[b] (nodal_size_field()), the other ranks' are empty.
   */
  void
  cap_master_contact_sizes(
    const std::array<ElasticBody *, 2>            &bodies,
    const std::array<unsigned int, 2>             &root,
    std::array<std::vector<SizeFieldTriangle>, 2> &fields);
} // namespace coulomb_adapt

#endif
