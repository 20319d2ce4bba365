#include <coulomb_adapt/indicator/pointwise_gap.h>

namespace coulomb_adapt
{
  QGaussLobatto<1>
  gap_sample_rule(const unsigned int degree)
  {
    return QGaussLobatto<1>(degree == 1 ? 2 : 9);
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
