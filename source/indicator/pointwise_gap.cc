#include <coulomb_adapt/indicator/pointwise_gap.h>

#include <algorithm>
#include <optional>

namespace coulomb_adapt
{
  QGaussLobatto<1>
  gap_sample_rule(const unsigned int degree)
  {
    return QGaussLobatto<1>(degree == 1 ? 2 : 9);
  }



  namespace
  {
    // The gap at parameter t of overlap o.
    double
    gap_at(const MortarInterface           &mortar,
           const unsigned int               o,
           const double                     t,
           const std::vector<Tensor<1, 2>> &slave_values,
           const std::vector<Tensor<1, 2>> &master_values)
    {
      return pointwise_gaps(mortar,
                            {mortar.overlap_point(o, t, 0.)},
                            slave_values,
                            master_values)[0];
    }



    // The vertex of the parabola through the gaps at the overlap's ends
    // and middle, where it opens upwards and lies inside.
    std::optional<double>
    parabola_vertex(const double g0, const double g_half, const double g1)
    {
      const double curvature = 2 * (g0 - 2 * g_half + g1); // g''/2
      const double slope     = g1 - g0 - curvature;        // g'(0)
      if (!(curvature > 0))
        return std::nullopt;
      const double t = -slope / (2 * curvature);
      if (t > 0 && t < 1)
        return t;
      return std::nullopt;
    }



    // The vertex of the parabola through (a, ga), (b, gb), (c, gc), a < b <
    // c; none where the three points are on a line.
    std::optional<double>
    vertex_through(const double a,
                   const double b,
                   const double c,
                   const double ga,
                   const double gb,
                   const double gc)
    {
      const double p = (b - a) * (gb - gc), q = (b - c) * (gb - ga);
      const double denominator = 2 * (p - q);
      if (!(denominator != 0))
        return std::nullopt;
      return b - ((b - a) * p - (b - c) * q) / denominator;
    }



    // On a curved overlap: from the smallest of the gap's samples,
    // successive parabolic interpolation through it and its neighbours,
    // each step keeping the three best points around the minimum (a
    // bracket a < b < c with g(b) <= g(a), g(c) that only shrinks), until
    // the bracket is 1e-10 of the overlap, a step lands outside it or on
    // b, or 50 steps. Where the smallest sample is an end, the gap may
    // still dip below it within the first (last) interval: the parabola
    // through the three end samples says where to look, and the bracket
    // starts there if the gap is lower; else none.
    std::optional<double>
    curved_gap_minimum(const MortarInterface           &mortar,
                       const unsigned int               o,
                       const std::vector<Tensor<1, 2>> &slave_values,
                       const std::vector<Tensor<1, 2>> &master_values,
                       const Quadrature<1>             &samples)
    {
      const unsigned int  n = samples.size();
      std::vector<double> t(n), g(n);
      for (unsigned int k = 0; k < n; ++k)
        {
          t[k] = samples.point(k)[0];
          g[k] = gap_at(mortar, o, t[k], slave_values, master_values);
        }
      const unsigned int i = std::min_element(g.begin(), g.end()) - g.begin();
      double             a, b, c, ga, gb, gc;
      if (i > 0 && i + 1 < n)
        {
          a  = t[i - 1];
          b  = t[i];
          c  = t[i + 1];
          ga = g[i - 1];
          gb = g[i];
          gc = g[i + 1];
        }
      else
        {
          // The end sample e and its neighbour f: a dip between them.
          const bool         first = i == 0;
          const unsigned int e = i, f = first ? 1 : n - 2,
                             m = first ? 2 : n - 3;
          const auto u         = first ?
                                   vertex_through(t[e], t[f], t[m], g[e], g[f], g[m]) :
                                   vertex_through(t[m], t[f], t[e], g[m], g[f], g[e]);
          if (!u || !(std::min(t[e], t[f]) < *u && *u < std::max(t[e], t[f])))
            return std::nullopt;
          const double gu = gap_at(mortar, o, *u, slave_values, master_values);
          if (!(gu < g[e]))
            return std::nullopt;
          a  = first ? t[e] : t[f];
          c  = first ? t[f] : t[e];
          ga = first ? g[e] : g[f];
          gc = first ? g[f] : g[e];
          b  = *u;
          gb = gu;
        }
      for (unsigned int step = 0; step < 50 && c - a > 1e-10; ++step)
        {
          const auto u = vertex_through(a, b, c, ga, gb, gc);
          if (!u || !(*u > a && *u < c) || *u == b)
            break;
          const double gu = gap_at(mortar, o, *u, slave_values, master_values);
          if (gu < gb)
            {
              (*u < b ? c : a)   = b;
              (*u < b ? gc : ga) = gb;
              b                  = *u;
              gb                 = gu;
            }
          else
            {
              (*u < b ? a : c)   = *u;
              (*u < b ? ga : gc) = gu;
            }
        }
      return b;
    }
  } // namespace



  std::vector<MortarInterface::OverlapPoint>
  interior_gap_minima(const MortarInterface           &mortar,
                      const std::vector<Tensor<1, 2>> &slave_values,
                      const std::vector<Tensor<1, 2>> &master_values)
  {
    std::vector<MortarInterface::OverlapPoint> minima;
    const unsigned int degree = mortar.slave_element_degree();
    if (degree < 2)
      return minima;
    AssertThrow(degree == 2,
                ExcNotImplemented(
                  "the gap's minima of segments of degree > 2"));
    const QGaussLobatto<1> samples = gap_sample_rule(degree);
    for (unsigned int o = 0; o < mortar.overlaps().size(); ++o)
      {
        std::optional<double> t;
        if (mortar.overlap_is_straight(o))
          t =
            parabola_vertex(gap_at(mortar, o, 0., slave_values, master_values),
                            gap_at(mortar, o, 0.5, slave_values, master_values),
                            gap_at(mortar, o, 1., slave_values, master_values));
        else
          t =
            curved_gap_minimum(mortar, o, slave_values, master_values, samples);
        if (t)
          minima.push_back(mortar.overlap_point(o, *t, 0.));
      }
    return minima;
  }



  Tensor<1, 2>
  gap_normal(const MortarInterface               &mortar,
             const MortarInterface::OverlapPoint &point)
  {
    const auto &overlap = mortar.overlaps()[point.overlap];
    const auto &segment = mortar.slave_segment_list()[overlap.slave_segment];
    if (!segment.curved)
      return segment.normal;
    const auto   phi = mortar.slave_shape_values(point.xi);
    Tensor<1, 2> n;
    for (unsigned int k = 0; k < segment.nodes.size(); ++k)
      n += phi[k] * mortar.slave_nodes()[segment.nodes[k]].normal;
    return n / n.norm();
  }



  double
  slave_bernstein_interpolant(const MortarInterface               &mortar,
                              const MortarInterface::OverlapPoint &point,
                              const std::vector<double>           &nodal_values)
  {
    const auto &segment =
      mortar
        .slave_segment_list()[mortar.overlaps()[point.overlap].slave_segment];
    const auto phi   = mortar.slave_bernstein_values(point.xi);
    double     value = 0;
    for (unsigned int k = 0; k < segment.nodes.size(); ++k)
      value += phi[k] * nodal_values[segment.nodes[k]];
    return value;
  }



  std::vector<double>
  pointwise_gaps(const MortarInterface                            &mortar,
                 const std::vector<MortarInterface::OverlapPoint> &points,
                 const std::vector<Tensor<1, 2>>                  &slave_values,
                 const std::vector<Tensor<1, 2>> &master_values)
  {
    const auto         &slave_segments  = mortar.slave_segment_list();
    const auto         &master_segments = mortar.master_segment_list();
    std::vector<double> gaps(points.size());
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const auto  &overlap = mortar.overlaps()[points[q].overlap];
        const auto  &s_seg   = slave_segments[overlap.slave_segment];
        const auto  &m_seg   = master_segments[overlap.master_segment];
        const auto   phi_s   = mortar.slave_shape_values(points[q].xi);
        const auto   phi_m   = mortar.master_shape_values(points[q].eta);
        Tensor<1, 2> jump;
        for (unsigned int k = 0; k < s_seg.nodes.size(); ++k)
          jump += phi_s[k] * slave_values[s_seg.nodes[k]];
        for (unsigned int k = 0; k < m_seg.nodes.size(); ++k)
          jump -= phi_m[k] * master_values[m_seg.nodes[k]];
        const Tensor<1, 2> n = gap_normal(mortar, points[q]);
        gaps[q] =
          (points[q].master_point - points[q].slave_point) * n - n * jump;
      }
    return gaps;
  }



  std::vector<double>
  pointwise_gaps(
    const MortarInterface                                      &mortar,
    const std::vector<MortarInterface::OverlapPoint>           &points,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements)
  {
    return pointwise_gaps(
      mortar,
      points,
      MortarInterface::gather_nodal_displacements(mortar.slave_nodes(),
                                                  *displacements[0]),
      MortarInterface::gather_nodal_displacements(mortar.master_nodes(),
                                                  *displacements[1]));
  }
} // namespace coulomb_adapt
