#ifndef coulomb_adapt_indicator_bernstein_contact_traction_h
#define coulomb_adapt_indicator_bernstein_contact_traction_h

#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/indicator/contact_error.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * The contact traction that the equilibrated stress of the CRE carries,
   * as coefficients (one set per slave node) in the slave segments'
   * Bernstein basis, which contact_traction_at() interpolates with.
   *
   * The Lagrange interpolant of admissible nodal tractions overshoots on
   * quadratic segments (hertz P2: a pressure down to -2.2 % of the
   * largest, where the zone opens and where the quadratic mortar's nodal
   * pressures alternate between end and middle nodes), and the bound for
   * mu = 0 needs sigma^'s pressure >= 0 everywhere. A polynomial whose
   * Bernstein coefficients lie in the Coulomb cone lies in it everywhere.
   * So: the Lagrange interpolant's own coefficients (the nodal values at
   * the ends, 2 v_m - (v_0 + v_1) / 2 at the middle node), the middle ones
   * raised as little as keeps each segment's traction in the cone
   * (c >= -sqrt(a b) for a quadratic with coefficients a, c, b). The projection adds force, and a body held by
   * contact alone in some direction (hertz's disc vertically) then no
   * longer balances its loads: the equilibration found a defect (7.9e-6
   * instead of 7e-12 on hertz P2). Every coefficient is therefore scaled
   * by 1 + a . v_j, v_j its share of the resultant force and of the moment
   * about the zone's centre, with a (3 x 3 least squares) such that force
   * and moment are those of the Lagrange interpolant of @p fields, which
   * the FE solution balances. Factors >= 0 keep the cone; should one be
   * negative, the Lagrange interpolant's coefficients are returned
   * unprojected (its negative pressure is then reported by the estimator,
   * and no bound claimed).
   *
   * Linear segments (their basis is the Bernstein basis, >= 0) return
   * @p fields as they are. Only the tractions change; gap and slip are
   * copied.
   */
  std::vector<ContactNodeFields>
  bernstein_contact_traction(const MortarInterface                &mortar,
                             const std::vector<ContactNodeFields> &fields,
                             const double friction_coefficient);
} // namespace coulomb_adapt

#endif
