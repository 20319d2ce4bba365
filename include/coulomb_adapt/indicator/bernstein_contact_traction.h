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
   * (c >= -sqrt(a b) for a quadratic with coefficients a, c, b). The projection
   * adds force, and a body held by contact alone in some direction (hertz's
   * disc vertically) then no longer balances its loads: the equilibration found
   * a defect (7.9e-6 instead of 7e-12 on hertz P2). Every coefficient is
   * therefore scaled by 1 + a . v_j, v_j its share of the resultant force and
   * of the moment about the zone's centre, with a (3 x 3 least squares) such
   * that force
   * and moment are those of the Lagrange interpolant of @p fields, which
   * the FE solution balances. Factors >= 0 keep the cone; should one be
   * negative, the Lagrange interpolant's coefficients are returned
   * unprojected (its negative pressure is then reported by the estimator,
   * and no bound claimed).
   *
   * The raise and the rescaling are repeated until a round raises nothing
   * or leaves force and moment restored to Report::tolerance (the
   * rescaling before it restored them as far as the shares can), at most
   * Report::max_rounds times; the report gives the
   * rounds, the defect left (restored: at most Report::tolerance, round-off
   * of the quadrature sums), and whether the Lagrange coefficients were
   * returned.
   *
   * Linear segments (their basis is the Bernstein basis, >= 0) return
   * @p fields as they are. Only the tractions change; gap and slip are
   * copied.
   */
  struct BernsteinContactTraction
  {
    /** One set per slave node: Bernstein coefficients on quadratic
     * segments, the nodal values on linear ones. */
    std::vector<ContactNodeFields> coefficients;
    /** What the construction did, for the log and summary.json. */
    struct Report
    {
      /** Quadratic segments, and those whose middle coefficient the cone
       * raised in the first round by more than 1e-8 of the largest nodal
       * traction (smaller raises, round-off of an open zone's pressures,
       * are made but not counted). */
      unsigned int n_segments = 0;
      unsigned int n_raised   = 0;
      /** Rescalings done (0: nothing was raised; with the Lagrange
       * fallback, those that succeeded before the one that failed). */
      unsigned int n_rounds = 0;
      /** |force and moment of the coefficients - those of the Lagrange
       * interpolant|, relative to the sum of the nodes' shares of the
       * latter (never 0 while there is any traction, unlike the resultant
       * of a self-balanced contact such as a press fit). 0 when nothing
       * was raised: the coefficients are the Lagrange interpolant's. */
      double resultant_defect = 0;
      /** A rescaling factor came out negative: the Lagrange interpolant's
       * coefficients are returned (not in the cone between the nodes). */
      bool lagrange_fallback = false;
      /** The defect is at round-off (hertz P2, mu = 0: 3.7e-3 after the
       * first raise, 9.8e-12 after the second, 1.7e-14 after the third). */
      bool
      resultant_restored() const
      {
        return resultant_defect <= tolerance;
      }
      static constexpr double       tolerance  = 1e-12;
      static constexpr unsigned int max_rounds = 8;
    } report;
  };

  BernsteinContactTraction
  bernstein_contact_traction(const MortarInterface                &mortar,
                             const std::vector<ContactNodeFields> &fields,
                             const double friction_coefficient);
} // namespace coulomb_adapt

#endif
