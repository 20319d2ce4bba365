#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/indicator/bernstein_contact_traction.h>
#include <coulomb_adapt/indicator/contact_correction.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace coulomb_adapt
{
  namespace
  {
    // The smallest middle coefficient c for which the quadratic with
    // Bernstein coefficients (a, c, b), a, b >= 0, is >= 0 on the whole
    // segment: its minimum, a b - c^2 over a + b - 2 c for c < 0, is >= 0
    // exactly when c >= -sqrt(a b).
    double
    lowest_middle_coefficient(const double a, const double b)
    {
      return -std::sqrt(std::max(a, 0.) * std::max(b, 0.));
    }

    // The middle coefficients of every segment moved as little as needed
    // for the segment's traction to lie in the Coulomb cone everywhere
    // (the ends are nodal values, in the cone): mu p + t >= 0 and
    // mu p - t >= 0, each a quadratic in Bernstein form; for mu = 0,
    // p >= 0 and t = 0.
    // Returns how many segments' middle coefficients moved at all, and by
    // more than @p significant (raises below it are round-off of the
    // open zone's pressures, 1e-10 of the peak on hertz, and differ
    // between rank counts).
    std::pair<unsigned int, unsigned int>
    project_middle_coefficients(
      const std::vector<MortarInterface::Segment> &segments,
      const double                                 mu,
      const double                                 significant,
      std::vector<ContactNodeFields>              &c)
    {
      unsigned int n_moved = 0, n_raised = 0;
      for (const auto &segment : segments)
        {
          const auto &a = c[segment.nodes[0]];
          const auto &b = c[segment.nodes[1]];
          auto       &m = c[segment.nodes[2]];
          if (mu == 0)
            {
              const double lowest =
                lowest_middle_coefficient(a.pressure, b.pressure);
              n_moved += (m.pressure < lowest);
              n_raised += (m.pressure < lowest - significant);
              m.pressure            = std::max(m.pressure, lowest);
              m.tangential_traction = 0;
              continue;
            }
          const auto side = [&](const ContactNodeFields &f, const double s) {
            return mu * f.pressure + s * f.tangential_traction;
          };
          const double lowest_plus =
            lowest_middle_coefficient(side(a, 1), side(b, 1));
          const double lowest_minus =
            lowest_middle_coefficient(side(a, -1), side(b, -1));
          n_moved += (side(m, 1) < lowest_plus) || (side(m, -1) < lowest_minus);
          n_raised += (side(m, 1) < lowest_plus - significant) ||
                      (side(m, -1) < lowest_minus - significant);
          const double plus     = std::max(side(m, 1), lowest_plus);
          const double minus    = std::max(side(m, -1), lowest_minus);
          m.pressure            = (plus + minus) / (2 * mu);
          m.tangential_traction = (plus - minus) / 2;
        }
      return {n_moved, n_raised};
    }

    // Force (x, y) and moment about @p centre, divided by @p length, of a
    // traction t applied at @p x: the three numbers that the equilibrium
    // of a body held by contact alone sees.
    std::array<double, 3>
    resultant_of(const Tensor<1, 2> &t,
                 const Point<2>     &x,
                 const Point<2>     &centre,
                 const double        length)
    {
      const Tensor<1, 2> r = x - centre;
      return {{t[0], t[1], (r[0] * t[1] - r[1] * t[0]) / length}};
    }

    // R = -lambda of one node's coefficients.
    Tensor<1, 2>
    traction_of(const MortarInterface::Node &node, const ContactNodeFields &f)
    {
      return -(f.pressure * node.normal + f.tangential_traction * node.tangent);
    }
  } // namespace



  BernsteinContactTraction
  bernstein_contact_traction(const MortarInterface                &mortar,
                             const std::vector<ContactNodeFields> &fields,
                             const double                          mu)
  {
    using Report = BernsteinContactTraction::Report;
    BernsteinContactTraction        result;
    std::vector<ContactNodeFields> &coefficients = result.coefficients;
    Report                         &report       = result.report;
    coefficients                                 = fields;
    if (mortar.slave_element_degree() == 1)
      return result;

    // The Lagrange interpolant's Bernstein coefficients.
    const auto &nodes    = mortar.slave_nodes();
    const auto &segments = mortar.slave_segment_list();
    for (const auto &segment : segments)
      {
        const auto &a = fields[segment.nodes[0]];
        const auto &b = fields[segment.nodes[1]];
        auto       &m = coefficients[segment.nodes[2]];
        m.pressure    = 2 * m.pressure - (a.pressure + b.pressure) / 2;
        m.tangential_traction =
          2 * m.tangential_traction -
          (a.tangential_traction + b.tangential_traction) / 2;
      }
    const std::vector<ContactNodeFields> lagrange = coefficients;
    report.n_segments                             = segments.size();

    // Resultants with the consistent load's quadrature (the load the
    // bodies balance), moments about the centroid of the overlaps.
    const auto points = mortar.overlap_quadrature(
      contact_traction_points_per_overlap(mortar.slave_element_degree()));
    Point<2> centre;
    double   length = 0;
    for (const auto &q : points)
      {
        centre += q.weight * (q.slave_point - Point<2>());
        length += q.weight;
      }
    if (length == 0)
      return result;
    centre /= length;
    // Each node's share of the resultant of @p values interpolated with
    // the Bernstein basis (or the Lagrange one).
    const auto shares_of = [&](const std::vector<ContactNodeFields> &values,
                               const bool bernstein) {
      std::vector<std::array<double, 3>> share(nodes.size(), {{0, 0, 0}});
      for (const auto &q : points)
        {
          const auto &segment =
            segments[mortar.overlaps()[q.overlap].slave_segment];
          const auto basis = bernstein ? mortar.slave_bernstein_values(q.xi) :
                                         mortar.slave_shape_values(q.xi);
          for (unsigned int k = 0; k < segment.nodes.size(); ++k)
            {
              const unsigned int j = segment.nodes[k];
              const auto         f = resultant_of(basis[k] * q.weight *
                                            traction_of(nodes[j], values[j]),
                                          q.slave_point,
                                          centre,
                                          length);
              for (unsigned int c = 0; c < 3; ++c)
                share[j][c] += f[c];
            }
        }
      return share;
    };
    // The scale of the defect is the sum of the nodes' shares, not the
    // resultant, which a self-balanced contact (a press fit) has near 0.
    std::array<double, 3> lagrange_resultant = {{0, 0, 0}};
    double                scale              = 0;
    for (const auto &v : shares_of(fields, false))
      {
        for (unsigned int c = 0; c < 3; ++c)
          lagrange_resultant[c] += v[c];
        scale += std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      }
    if (scale == 0)
      return result;
    // A raise counts in the report where it exceeds 1e-8 of the largest
    // nodal traction, the threshold of the negative-pressure check.
    double largest_traction = 0;
    for (const auto &f : fields)
      largest_traction =
        std::max(largest_traction,
                 std::abs(f.pressure) + std::abs(f.tangential_traction));
    const double significant = 1e-8 * largest_traction;

    // Raise, restore the resultant by factors 1 + a . v_j, and again: a
    // factor != 1 can move a tight middle coefficient out of the cone
    // again, by a fraction of the factors' spread (0.4 % on hertz P2), so
    // each round's raise is that much smaller. One rescaling restores the
    // resultant as far as the shares can (a is the least-squares
    // solution), so the loop ends when a round raises nothing, or raises
    // so little that the resultant is still restored to round-off (with
    // friction the two cone sides keep nudging each other at 1e-17).
    for (unsigned int round = 0;; ++round)
      {
        const auto [n_moved, n_raised] =
          project_middle_coefficients(segments, mu, significant, coefficients);
        if (round == 0)
          {
            report.n_raised = n_raised;
            // Nothing moved: the Lagrange interpolant itself, whose
            // resultant is the one to keep (defect 0).
            if (n_moved == 0)
              return result;
          }
        const auto share = shares_of(coefficients, true);
        // G a = V_L - V, G = sum_j v_j v_j^T, by the pseudo-inverse (a
        // straight frictionless zone has no tangential force to adjust).
        LAPACKFullMatrix<double> G(3, 3);
        Vector<double>           difference(3);
        for (unsigned int c = 0; c < 3; ++c)
          difference(c) = lagrange_resultant[c];
        for (const auto &v : share)
          for (unsigned int c = 0; c < 3; ++c)
            {
              difference(c) -= v[c];
              for (unsigned int d = 0; d < 3; ++d)
                G(c, d) += v[c] * v[d];
            }
        report.resultant_defect = difference.l2_norm() / scale;
        report.n_rounds         = round;
        if ((round > 0 && (n_moved == 0 || report.resultant_restored())) ||
            round == Report::max_rounds)
          return result;
        G.compute_inverse_svd(1e-12);
        Vector<double> a(3);
        G.vmult(a, difference);
        for (unsigned int j = 0; j < nodes.size(); ++j)
          {
            const double factor =
              1 + a(0) * share[j][0] + a(1) * share[j][1] + a(2) * share[j][2];
            // Not possible within the cone: the Lagrange interpolant, whose
            // negative pressure the caller reports.
            if (factor < 0)
              {
                coefficients             = lagrange;
                report.lagrange_fallback = true;
                report.resultant_defect  = 0;
                return result;
              }
            coefficients[j].pressure *= factor;
            coefficients[j].tangential_traction *= factor;
          }
      }
  }
} // namespace coulomb_adapt
