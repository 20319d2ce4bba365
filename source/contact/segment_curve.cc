#include <coulomb_adapt/contact/segment_curve.h>

#include <cmath>

namespace coulomb_adapt
{
  namespace mortar
  {
    std::vector<double>
    segment_shape_values(const unsigned int degree, const double xi)
    {
      if (degree == 1)
        return {1 - xi, xi};
      return {(1 - xi) * (1 - 2 * xi), xi * (2 * xi - 1), 4 * xi * (1 - xi)};
    }



    std::vector<double>
    segment_bernstein_values(const unsigned int degree, const double xi)
    {
      if (degree == 1)
        return segment_shape_values(degree, xi);
      return {(1 - xi) * (1 - xi), xi * xi, 2 * xi * (1 - xi)};
    }



    std::vector<double>
    segment_shape_derivatives(const unsigned int degree, const double xi)
    {
      if (degree == 1)
        return {-1, 1};
      return {4 * xi - 3, 4 * xi - 1, 4 - 8 * xi};
    }



    Point<2>
    SegmentCurve::value(const double xi) const
    {
      const auto phi = segment_shape_values(degree, xi);
      Point<2>   x;
      for (unsigned int k = 0; k < points.size(); ++k)
        x += phi[k] * (points[k] - Point<2>());
      return x;
    }



    Tensor<1, 2>
    SegmentCurve::derivative(const double xi) const
    {
      const auto   dphi = segment_shape_derivatives(degree, xi);
      Tensor<1, 2> t;
      for (unsigned int k = 0; k < points.size(); ++k)
        t += dphi[k] * (points[k] - Point<2>());
      return t;
    }



    Tensor<1, 2>
    SegmentCurve::second_derivative() const
    {
      if (degree == 1)
        return Tensor<1, 2>();
      return 4 * (points[0] - Point<2>()) + 4 * (points[1] - Point<2>()) -
             8 * (points[2] - Point<2>());
    }



    Tensor<1, 2>
    SegmentCurve::normal(const double xi, const Tensor<1, 2> &outward) const
    {
      const Tensor<1, 2> t = derivative(xi);
      Tensor<1, 2>       n({t[1], -t[0]});
      n /= n.norm();
      return n * outward < 0 ? -n : n;
    }



    double
    SegmentCurve::orthogonal_projection(const Point<2> &p) const
    {
      const Tensor<1, 2> chord = points[1] - points[0];
      double             xi    = (p - points[0]) * chord / chord.norm_square();
      for (unsigned int it = 0; it < 20; ++it)
        {
          const Tensor<1, 2> r = p - value(xi), t = derivative(xi);
          const double       f    = r * t;
          const double       df   = -t.norm_square() + r * second_derivative();
          const double       step = f / df;
          xi -= step;
          if (std::abs(step) < 1e-15)
            break;
        }
      return xi;
    }



    std::pair<double, double>
    intersect_along(const SegmentCurve &master,
                    const Point<2>     &x,
                    const Tensor<1, 2> &n,
                    double              eta)
    {
      double t = (master.value(eta) - x) * n;
      for (unsigned int it = 0; it < 20; ++it)
        {
          // F = y(eta) - x - t n; dF = [y'(eta), -n].
          const Tensor<1, 2> F     = master.value(eta) - x - t * n;
          const Tensor<1, 2> dy    = master.derivative(eta);
          const double       det   = -dy[0] * n[1] + dy[1] * n[0];
          const double       d_eta = (-F[0] * n[1] + F[1] * n[0]) / det;
          const double       d_t   = (dy[0] * F[1] - dy[1] * F[0]) / det;
          eta -= d_eta;
          t -= d_t;
          if (std::abs(d_eta) < 1e-15 &&
              std::abs(d_t) < 1e-15 * (1 + std::abs(t)))
            break;
        }
      return {eta, t};
    }
  } // namespace mortar
} // namespace coulomb_adapt
