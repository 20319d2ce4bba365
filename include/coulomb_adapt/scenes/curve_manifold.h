#ifndef coulomb_adapt_scenes_curve_manifold_h
#define coulomb_adapt_scenes_curve_manifold_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria.h>

#include <map>
#include <memory>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * A smooth curve of a gmsh geometry (a spline, B-spline, Bezier curve or
   * ellipse of a .geo file) as points of it along gmsh's parametrisation:
   * each with its parameter and the derivative there, dense enough that the
   * cubic Hermite interpolation between them is the curve to a tolerance
   * (scenes/gmsh_bodies.cc samples it while gmsh has the model). Numbers
   * only, so that the rank that read the file can give it to the others.
   */
  struct CurveSamples
  {
    /** gmsh's parameter t of each point, increasing. */
    std::vector<double>   parameters;
    std::vector<Point<2>> points;
    /** dx/dt at each point. */
    std::vector<Tensor<1, 2>> derivatives;
    /** Whether the curve is closed (its last point is its first). */
    bool closed = false;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &parameters &points &derivatives &closed;
    }
  };

  /** The sampled curves of a gmsh geometry, by the manifold id that the
   * boundary lines on them carry. */
  using SampledCurves = std::map<types::manifold_id, CurveSamples>;

  /**
   * The manifold of a sampled curve (CurveSamples): the chart is the arc
   * length s along the curve (from its first point), so that the new point
   * of a face refined is the middle of its arc, and push_forward(s) is the
   * cubic Hermite interpolation of the samples, with gmsh's derivatives,
   * between the two samples around s (s is linear in gmsh's parameter
   * between two samples). pull_back() is the closest point of the curve
   * (the nearest samples, then Newton's method on their intervals). A
   * closed curve is periodic in s with its length.
   *
   * Clones share the samples (they never change), so the Triangulations
   * that hold the manifold may copy it freely.
   */
  class CurveManifold : public ChartManifold<2, 2, 1>
  {
  public:
    explicit CurveManifold(const CurveSamples &samples);

    std::unique_ptr<Manifold<2>>
    clone() const override;

    Point<1>
    pull_back(const Point<2> &x) const override;

    Point<2>
    push_forward(const Point<1> &s) const override;

    DerivativeForm<1, 1, 2>
    push_forward_gradient(const Point<1> &s) const override;

    /** The point of the curve closest to @p x. */
    Point<2>
    project(const Point<2> &x) const;

    /** The curve's length (of its Hermite interpolation's chords). */
    double
    length() const;

    /** How many sample intervals the curve has. */
    unsigned int
    n_intervals() const;

    bool
    is_closed() const;

  private:
    struct Curve;

    explicit CurveManifold(const std::shared_ptr<const Curve> &curve);

    std::shared_ptr<const Curve> curve;
  };

  /** The cubic Hermite interpolant between @p x0 and @p x1 with the
   * derivatives @p d0, @p d1 in a parameter that runs over @p step, at
   * the fraction @p u of the step. */
  inline Point<2>
  cubic_hermite(const Point<2>     &x0,
                const Tensor<1, 2> &d0,
                const Point<2>     &x1,
                const Tensor<1, 2> &d1,
                const double        step,
                const double        u)
  {
    const double u2 = u * u, u3 = u2 * u;
    return Point<2>((2 * u3 - 3 * u2 + 1) * x0 + (u3 - 2 * u2 + u) * step * d0 +
                    (-2 * u3 + 3 * u2) * x1 + (u3 - u2) * step * d1);
  }

  /** Attach a CurveManifold for each curve of @p curves to its manifold id
   * in @p tria. */
  void
  attach_curve_manifolds(const SampledCurves &curves, Triangulation<2> &tria);
} // namespace coulomb_adapt

#endif
