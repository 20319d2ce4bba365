#include <deal.II/base/exceptions.h>

#include <deal.II/numerics/rtree.h>

#include <coulomb_adapt/scenes/curve_manifold.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

namespace coulomb_adapt
{
  // The samples with their arc lengths and a search tree over their points.
  // Between samples i and i + 1 the curve is the cubic Hermite interpolant
  // H_i(u), u in [0, 1], of the points and of gmsh's derivatives times the
  // parameter step; s is linear in u there, s_i + u (s_{i+1} - s_i), with
  // s_{i+1} - s_i the chord (within (h kappa)^2 / 24 of the arc).
  struct CurveManifold::Curve
  {
    explicit Curve(const CurveSamples &samples);

    unsigned int
    n_intervals() const
    {
      return points.size() - 1;
    }

    // H_i(u) and its first two derivatives in u.
    Point<2>
    value(const unsigned int i, const double u) const;
    Tensor<1, 2>
    derivative(const unsigned int i, const double u) const;
    Tensor<1, 2>
    second_derivative(const unsigned int i, const double u) const;

    // The interval of arc length @p s (reduced to the curve), and u there.
    std::pair<unsigned int, double>
    locate(double s) const;

    // The closest point of interval @p i to @p x: its u.
    double
    closest_on_interval(const unsigned int i, const Point<2> &x) const;

    std::vector<double>                      steps; // t_{i+1} - t_i
    std::vector<Point<2>>                    points;
    std::vector<Tensor<1, 2>>                derivatives;
    std::vector<double>                      arc_lengths;
    bool                                     closed;
    RTree<std::pair<Point<2>, unsigned int>> tree;
  };



  CurveManifold::Curve::Curve(const CurveSamples &samples)
    : closed(samples.closed)
  {
    AssertThrow(samples.points.size() >= 2 &&
                  samples.points.size() == samples.parameters.size() &&
                  samples.points.size() == samples.derivatives.size(),
                ExcMessage("a sampled curve needs at least two samples, each "
                           "with its parameter and derivative"));
    // A sample at the place of the one before (a degenerate curve) would
    // give an interval of length zero: skip it.
    std::vector<unsigned int> kept = {0};
    for (unsigned int k = 1; k < samples.points.size(); ++k)
      if (samples.points[k] != samples.points[kept.back()])
        kept.push_back(k);
    AssertThrow(kept.size() >= 2,
                ExcMessage("a sampled curve has all its points at one place"));
    std::vector<std::pair<Point<2>, unsigned int>> leaves;
    for (unsigned int j = 0; j < kept.size(); ++j)
      {
        const unsigned int k = kept[j];
        points.push_back(samples.points[k]);
        derivatives.push_back(samples.derivatives[k]);
        leaves.emplace_back(samples.points[k], j);
        if (j == 0)
          arc_lengths.push_back(0);
        else
          {
            steps.push_back(samples.parameters[k] -
                            samples.parameters[kept[j - 1]]);
            arc_lengths.push_back(arc_lengths.back() +
                                  points[j].distance(points[j - 1]));
          }
      }
    tree = pack_rtree(leaves);
  }



  Point<2>
  CurveManifold::Curve::value(const unsigned int i, const double u) const
  {
    return cubic_hermite(points[i],
                         derivatives[i],
                         points[i + 1],
                         derivatives[i + 1],
                         steps[i],
                         u);
  }



  Tensor<1, 2>
  CurveManifold::Curve::derivative(const unsigned int i, const double u) const
  {
    const double u2 = u * u, h = steps[i];
    return (6 * u2 - 6 * u) * points[i] +
           (3 * u2 - 4 * u + 1) * h * derivatives[i] +
           (-6 * u2 + 6 * u) * points[i + 1] +
           (3 * u2 - 2 * u) * h * derivatives[i + 1];
  }



  Tensor<1, 2>
  CurveManifold::Curve::second_derivative(const unsigned int i,
                                          const double       u) const
  {
    const double h = steps[i];
    return (12 * u - 6) * points[i] + (6 * u - 4) * h * derivatives[i] +
           (-12 * u + 6) * points[i + 1] + (6 * u - 2) * h * derivatives[i + 1];
  }



  std::pair<unsigned int, double>
  CurveManifold::Curve::locate(double s) const
  {
    const double length = arc_lengths.back();
    if (closed)
      s -= length * std::floor(s / length);
    s                    = std::clamp(s, 0., length);
    const unsigned int i = std::min<unsigned int>(
      std::upper_bound(arc_lengths.begin(), arc_lengths.end(), s) -
        arc_lengths.begin() - 1,
      n_intervals() - 1);
    return {i, (s - arc_lengths[i]) / (arc_lengths[i + 1] - arc_lengths[i])};
  }



  // Newton's method on (H(u) - x) . H'(u) = 0 from the projection onto the
  // chord, kept in [0, 1]; where the second derivative of the distance is
  // not positive, a Gauss-Newton step.
  double
  CurveManifold::Curve::closest_on_interval(const unsigned int i,
                                            const Point<2>    &x) const
  {
    const Tensor<1, 2> chord = points[i + 1] - points[i];
    double             u =
      std::clamp((x - points[i]) * chord / chord.norm_square(), 0., 1.);
    for (unsigned int iteration = 0; iteration < 50; ++iteration)
      {
        const Tensor<1, 2> r  = value(i, u) - x;
        const Tensor<1, 2> d1 = derivative(i, u);
        const double       f  = r * d1;
        double             df = d1 * d1 + r * second_derivative(i, u);
        if (!(df > 0))
          df = d1 * d1;
        const double next = std::clamp(u - f / df, 0., 1.);
        const double step = std::abs(next - u);
        u                 = next;
        if (step < 1e-15)
          break;
      }
    return u;
  }



  CurveManifold::CurveManifold(const CurveSamples &samples)
    : CurveManifold(std::make_shared<const Curve>(samples))
  {}



  CurveManifold::CurveManifold(const std::shared_ptr<const Curve> &curve)
    : ChartManifold<2, 2, 1>(curve->closed ?
                               Tensor<1, 1>({curve->arc_lengths.back()}) :
                               Tensor<1, 1>())
    , curve(curve)
  {}



  std::unique_ptr<Manifold<2>>
  CurveManifold::clone() const
  {
    return std::unique_ptr<Manifold<2>>(new CurveManifold(curve));
  }



  // The closest point lies on an interval next to one of the samples
  // nearest to x (a few of them, for points where the curve comes back
  // near itself).
  Point<1>
  CurveManifold::pull_back(const Point<2> &x) const
  {
    std::vector<std::pair<Point<2>, unsigned int>> nearest;
    curve->tree.query(boost::geometry::index::nearest(x, 4),
                      std::back_inserter(nearest));
    const unsigned int n        = curve->n_intervals();
    double             best     = std::numeric_limits<double>::max();
    double             best_s   = 0;
    const auto         consider = [&](const unsigned int i) {
      const double u        = curve->closest_on_interval(i, x);
      const double distance = curve->value(i, u).distance_square(x);
      if (distance < best)
        {
          best   = distance;
          best_s = curve->arc_lengths[i] +
                   u * (curve->arc_lengths[i + 1] - curve->arc_lengths[i]);
        }
    };
    for (const auto &[point, j] : nearest)
      {
        if (j < n)
          consider(j);
        if (j > 0)
          consider(j - 1);
        else if (curve->closed)
          consider(n - 1);
        if (j == n && curve->closed)
          consider(0);
      }
    if (curve->closed && best_s >= length())
      best_s -= length();
    return Point<1>(best_s);
  }



  Point<2>
  CurveManifold::push_forward(const Point<1> &s) const
  {
    const auto [i, u] = curve->locate(s[0]);
    return curve->value(i, u);
  }



  DerivativeForm<1, 1, 2>
  CurveManifold::push_forward_gradient(const Point<1> &s) const
  {
    const auto [i, u] = curve->locate(s[0]);
    const Tensor<1, 2> dx_ds =
      curve->derivative(i, u) /
      (curve->arc_lengths[i + 1] - curve->arc_lengths[i]);
    DerivativeForm<1, 1, 2> gradient;
    for (unsigned int d = 0; d < 2; ++d)
      gradient[d][0] = dx_ds[d];
    return gradient;
  }



  Point<2>
  CurveManifold::project(const Point<2> &x) const
  {
    return push_forward(pull_back(x));
  }



  double
  CurveManifold::length() const
  {
    return curve->arc_lengths.back();
  }



  unsigned int
  CurveManifold::n_intervals() const
  {
    return curve->n_intervals();
  }



  bool
  CurveManifold::is_closed() const
  {
    return curve->closed;
  }



  void
  attach_curve_manifolds(const SampledCurves &curves, Triangulation<2> &tria)
  {
    for (const auto &[id, samples] : curves)
      tria.set_manifold(id, CurveManifold(samples));
  }
} // namespace coulomb_adapt
