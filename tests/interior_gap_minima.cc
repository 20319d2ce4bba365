// The gap's smallest values between the samples of the mortar's overlaps
// (interior_gap_minima(), used by the CRE's kinematic side,
// doc/indicator.md section 4c).
//
// Straight overlaps, against a gap known in closed form. Patch scene,
// non-matching interface (3 slave vs 10 master cells), P2 triangles and
// Q2 quadrilaterals: the interface is the line y = const, n = (0, -1),
// zero initial gap, so the gap is g = u_s,y - u_m,y. With
// u_s,y = c1 (x - a)^2 and u_m,y = -c2 (x - b)^2 + d (both interpolated
// exactly by the quadratic segments) g = c1 (x - a)^2 + c2 (x - b)^2 - d:
// a parabola with its vertex at x* = (c1 a + c2 b) / (c1 + c2) and
// g(x*) = c1 c2 (a - b)^2 / (c1 + c2) - d. Exactly one overlap contains
// x*, so exactly one point is returned, at x*, with that gap. A
// parabola that opens downwards, and a linear gap, have their smallest
// values at overlaps' ends: no point. Linear segments: no point.
//
// Curved overlaps (hertz), against a dense sampling: check_curved().

#include <coulomb_adapt/indicator/pointwise_gap.h>

#include "mortar_test_utilities.h"

#include <algorithm>
#include <cmath>
#include <functional>

using namespace coulomb_adapt;

namespace
{
  std::vector<Tensor<1, 2>>
  vertical(const std::vector<MortarInterface::Node>  &nodes,
           const std::function<double(const double)> &u_y)
  {
    std::vector<Tensor<1, 2>> values;
    for (const auto &node : nodes)
      values.push_back(Tensor<1, 2>({0., u_y(node.position[0])}));
    return values;
  }



  void
  check(const std::string &cell_type, const std::string &degree)
  {
    const testing::SceneInterface interface(
      {{"Scene/Name", "patch"},
       {"Mesh/Cell type", cell_type},
       {"Finite elements/Polynomial degree", degree},
       {"Scene/Patch/Upper body subdivisions", "3, 2"},
       {"Scene/Patch/Lower body subdivisions", "10, 4"}});
    const MortarInterface &mortar = interface.mortar;

    double x_min = 1e300, x_max = -1e300;
    for (const auto &node : mortar.slave_nodes())
      {
        x_min = std::min(x_min, node.position[0]);
        x_max = std::max(x_max, node.position[0]);
      }
    // Vertex at 0.4567 of the interface: inside an overlap, not at a node.
    const double length = x_max - x_min;
    const double a = x_min + 0.31 * length, b = x_min + 0.53 * length;
    const double c1 = 1e-3, c2 = 2e-3, d = 5e-3;
    const double x_vertex = (c1 * a + c2 * b) / (c1 + c2);
    const double g_vertex = c1 * c2 * (a - b) * (a - b) / (c1 + c2) - d;

    const auto upwards = interior_gap_minima(
      mortar,
      vertical(mortar.slave_nodes(),
               [&](const double x) { return c1 * (x - a) * (x - a); }),
      vertical(mortar.master_nodes(),
               [&](const double x) { return -c2 * (x - b) * (x - b) + d; }));
    const auto downwards = interior_gap_minima(
      mortar,
      vertical(mortar.slave_nodes(),
               [&](const double x) { return -c1 * (x - a) * (x - a); }),
      vertical(mortar.master_nodes(),
               [&](const double x) { return c2 * (x - b) * (x - b) + d; }));
    const auto linear = interior_gap_minima(
      mortar,
      vertical(mortar.slave_nodes(),
               [&](const double x) { return 1e-3 * (x - a); }),
      vertical(mortar.master_nodes(), [](const double) { return 0.; }));

    auto out = testing::root_output();
    out << cell_type << ", degree " << degree << ": "
        << mortar.overlaps().size()
        << " overlaps; upward parabola: " << upwards.size() << " point(s)";
    if (degree == "1")
      {
        out << ", downward: " << downwards.size()
            << ", linear: " << linear.size() << std::endl;
        AssertThrow(upwards.empty() && downwards.empty() && linear.empty(),
                    ExcMessage("linear segments have no interior minimum"));
        return;
      }
    AssertThrow(upwards.size() == 1,
                ExcMessage("expected the one vertex, got " +
                           std::to_string(upwards.size()) + " points"));
    const auto  &point   = upwards[0];
    const double g_found = pointwise_gaps(
      mortar,
      upwards,
      vertical(mortar.slave_nodes(),
               [&](const double x) { return c1 * (x - a) * (x - a); }),
      vertical(mortar.master_nodes(),
               [&](const double x) { return -c2 * (x - b) * (x - b) + d; }))[0];
    const double x_error = std::abs(point.slave_point[0] - x_vertex) / length;
    const double g_error = std::abs(g_found - g_vertex) / d;
    out << " at x* within " << (x_error < 1e-13 ? "1e-13" : "MORE")
        << " of the interface's length, gap there = c1 c2 (a - b)^2 / (c1 + "
           "c2) - d within "
        << (g_error < 1e-12 ? "1e-12" : "MORE") << " of d ("
        << std::setprecision(6) << g_vertex
        << " mm); downward: " << downwards.size()
        << ", linear: " << linear.size() << std::endl;
    AssertThrow(x_error < 1e-13 && g_error < 1e-12,
                ExcMessage("vertex off: x " + std::to_string(x_error) +
                           ", gap " + std::to_string(g_error)));
    AssertThrow(downwards.empty() && linear.empty(),
                ExcMessage("a point where the smallest gap is at an end"));
  }



  // Curved segments (hertz, P2 triangles: the disc's faces are parabolas
  // through a point of the circle): the gap is smooth but no polynomial.
  // With the disc tilted, u_s = (0, -alpha x), its smallest value moves
  // off the disc's lowest node to about x = alpha R. Truth: the gaps at
  // 2,001 equidistant points of every curved overlap. The minimum found
  // can only be below their smallest, by at most what a parabola of
  // curvature g'' = 1/R dips between two of them, (1/R)/2 (Delta/2)^2
  // with Delta the overlap's length / 2000 (checked with a factor 2), and
  // it must undercut the 9 samples' smallest. With @p in_end_interval
  // alpha puts the minimum inside the first of the 8 sample intervals of
  // the overlap that held it, where the smallest sample of that overlap
  // is its end.
  void
  check_curved(const bool in_end_interval)
  {
    const testing::SceneInterface interface(
      {{"Scene/Name", "hertz"},
       {"Mesh/Cell type", "triangle"},
       {"Finite elements/Polynomial degree", "2"}});
    const MortarInterface &mortar         = interface.mortar;
    const double           radius         = 100; // the scene's default 'Radius'
    const double           first_interval = gap_sample_rule(2).point(1)[0];

    double alpha = 1.234e-3;
    if (in_end_interval)
      {
        // The overlap where alpha = 1.234e-3 puts the minimum, and the
        // middle of its first sample interval.
        const auto tilted = interior_gap_minima(
          mortar,
          vertical(mortar.slave_nodes(),
                   [&](const double x) { return -alpha * x; }),
          vertical(mortar.master_nodes(), [](const double) { return 0.; }));
        AssertThrow(tilted.size() == 1, ExcInternalError());
        alpha = mortar.overlap_point(tilted[0].overlap, first_interval / 2, 0.)
                  .slave_point[0] /
                radius;
      }
    const auto slave_values =
      vertical(mortar.slave_nodes(),
               [&](const double x) { return -alpha * x; });
    const auto master_values =
      vertical(mortar.master_nodes(), [](const double) { return 0.; });

    std::vector<MortarInterface::OverlapPoint> dense;
    unsigned int                               n_curved = 0;
    for (unsigned int o = 0; o < mortar.overlaps().size(); ++o)
      if (!mortar.overlap_is_straight(o))
        {
          ++n_curved;
          for (unsigned int k = 0; k <= 2000; ++k)
            dense.push_back(mortar.overlap_point(o, k / 2000., 0.));
        }
    const std::vector<double> dense_gaps =
      pointwise_gaps(mortar, dense, slave_values, master_values);
    const unsigned int k_dense =
      std::min_element(dense_gaps.begin(), dense_gaps.end()) -
      dense_gaps.begin();
    const std::vector<double> sample_gaps =
      pointwise_gaps(mortar,
                     mortar.overlap_quadrature(gap_sample_rule(2)),
                     slave_values,
                     master_values);
    const double sample_min =
      *std::min_element(sample_gaps.begin(), sample_gaps.end());

    const auto minima =
      interior_gap_minima(mortar, slave_values, master_values);
    AssertThrow(!minima.empty(), ExcMessage("no minimum on curved overlaps"));
    const std::vector<double> minima_gaps =
      pointwise_gaps(mortar, minima, slave_values, master_values);
    const unsigned int k_found =
      std::min_element(minima_gaps.begin(), minima_gaps.end()) -
      minima_gaps.begin();
    const double overlap_length =
      (mortar.overlap_point(dense[k_dense].overlap, 1., 0.).slave_point -
       mortar.overlap_point(dense[k_dense].overlap, 0., 0.).slave_point)
        .norm();
    const double dip =
      2 * (1 / radius) / 2 * std::pow(overlap_length / 2000 / 2, 2);
    const double scale = std::abs(dense_gaps[k_dense]);
    const double below = dense_gaps[k_dense] - minima_gaps[k_found];
    const double x_error =
      std::abs(minima[k_found].slave_point[0] - dense[k_dense].slave_point[0]);

    const auto  &overlap = mortar.overlaps()[minima[k_found].overlap];
    const double t_found =
      (minima[k_found].xi - overlap.begin) / (overlap.end - overlap.begin);
    const bool in_first_interval =
      std::min(t_found, 1 - t_found) < first_interval;

    auto out = testing::root_output();
    out << "hertz, P2 triangles, disc tilted"
        << (in_end_interval ? " to a minimum in an end interval" : "") << ": "
        << n_curved << " curved overlaps; smallest gap inside them "
        << std::setprecision(6) << minima_gaps[k_found]
        << " mm at x = " << minima[k_found].slave_point[0]
        << (in_first_interval ? ", between an end and the next sample" : "")
        << "; below the 2,001-point sampling's smallest by "
        << (below >= -1e-14 * scale && below <= dip ? "no more than" :
                                                      "MORE than")
        << " a parabola's dip between its points; 9 samples' smallest "
        << sample_min << " mm" << std::endl;
    AssertThrow(n_curved > 0, ExcMessage("no curved overlap"));
    AssertThrow(below >= -1e-14 * scale && below <= dip && x_error < 1e-3,
                ExcMessage("curved minimum off: " + std::to_string(below) +
                           " below the sampling, x off by " +
                           std::to_string(x_error)));
    AssertThrow(minima_gaps[k_found] < sample_min,
                ExcMessage("the samples already saw the minimum"));
    AssertThrow(in_first_interval == in_end_interval,
                ExcMessage("the minimum is not where the tilt put it"));
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check("triangle", "2");
  check("quadrilateral", "2");
  check("triangle", "1");
  check_curved(false);
  check_curved(true);
}
