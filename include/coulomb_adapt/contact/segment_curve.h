#ifndef coulomb_adapt_contact_segment_curve_h
#define coulomb_adapt_contact_segment_curve_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <utility>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The geometry of one contact segment of the mortar interface: the
   * curve through its nodes that the element's mapping makes of a face,
   * and where a line meets it.
   */
  namespace mortar
  {
    /** Shape functions of a contact segment of degree 1 or 2 in the
     * parameter xi in [0, 1] along its chord: the two end nodes, then (for
     * degree 2) the middle node. */
    std::vector<double>
    segment_shape_values(const unsigned int degree, const double xi);

    /** The Bernstein polynomials of the same degree, in the same order
     * (for degree 2: (1 - xi)^2, xi^2, 2 xi (1 - xi)). They are >= 0, so
     * a polynomial with coefficients >= 0 in this basis is >= 0 on the
     * whole segment, which the Lagrange interpolant of nodal values >= 0
     * is not for degree 2. For degree 1 they are segment_shape_values. */
    std::vector<double>
    segment_bernstein_values(const unsigned int degree, const double xi);

    /** Derivatives of segment_shape_values in xi. */
    std::vector<double>
    segment_shape_derivatives(const unsigned int degree, const double xi);

    /**
     * The image of a segment: the curve through its nodes (ends, then the
     * middle node) that the element's mapping makes of the face, x(xi) =
     * sum_k phi_k(xi) X_k. Straight for degree 1 and for a middle node at
     * the chord's midpoint; a parabola through a point on the boundary's
     * manifold otherwise.
     */
    struct SegmentCurve
    {
      std::vector<Point<2>> points;
      unsigned int          degree;

      Point<2>
      value(const double xi) const;

      Tensor<1, 2>
      derivative(const double xi) const;

      Tensor<1, 2>
      second_derivative() const;

      /** The unit normal at xi, on the side of @p outward. */
      Tensor<1, 2>
      normal(const double xi, const Tensor<1, 2> &outward) const;

      /** The parameter of the point of the curve nearest to @p p (where
       * p - x(xi) is normal to the curve), by Newton's method from the
       * chord's parameter; not limited to [0, 1]. */
      double
      orthogonal_projection(const Point<2> &p) const;
    };

    /** Where the line x + t n meets the curve @p master: its parameter eta
     * and t, by Newton's method from @p eta (the chord's solution). */
    std::pair<double, double>
    intersect_along(const SegmentCurve &master,
                    const Point<2>     &x,
                    const Tensor<1, 2> &n,
                    double              eta);
  } // namespace mortar
} // namespace coulomb_adapt

#endif
