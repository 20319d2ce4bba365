#include <coulomb_adapt/indicator/pointwise_gap.h>

namespace coulomb_adapt
{
  QGaussLobatto<1>
  gap_sample_rule(const unsigned int degree)
  {
    return QGaussLobatto<1>(degree == 1 ? 2 : 9);
  }



  std::vector<double>
  pointwise_gaps(const MortarInterface                            &mortar,
                 const std::vector<MortarInterface::OverlapPoint> &points,
                 const std::vector<Tensor<1, 2>>                  &slave_values,
                 const std::vector<Tensor<1, 2>> &master_values)
  {
    const auto         &slave_nodes     = mortar.slave_nodes();
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
        Tensor<1, 2> jump, n;
        for (unsigned int k = 0; k < s_seg.nodes.size(); ++k)
          {
            jump += phi_s[k] * slave_values[s_seg.nodes[k]];
            n += phi_s[k] * slave_nodes[s_seg.nodes[k]].normal;
          }
        for (unsigned int k = 0; k < m_seg.nodes.size(); ++k)
          jump -= phi_m[k] * master_values[m_seg.nodes[k]];
        n = s_seg.curved ? n / n.norm() : s_seg.normal;
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
