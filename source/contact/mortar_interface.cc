#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <coulomb_adapt/contact/mortar_interface.h>

#include <algorithm>
#include <cmath>

namespace coulomb_adapt
{
  void
  MortarInterface::collect_contact_boundary(const ElasticBody &   body,
                                            std::vector<Node> &   nodes,
                                            std::vector<Segment> &segments)
  {
    const DoFHandler<2> &dof_handler = body.dof_handler();
    AssertThrow(dof_handler.get_fe().degree == 1,
                ExcMessage("The mortar contact interface supports linear "
                           "elements (Q1/P1) so far; set 'Finite "
                           "elements/Polynomial degree = 1'."));
    const types::boundary_id contact_id = body.description().contact_boundary_id;

    // Per local contact face: 2 x (x, y, dof_x, dof_y) and the normal.
    std::vector<double> local;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->boundary_id() == contact_id)
            {
              const Tensor<1, 2> edge = face->vertex(1) - face->vertex(0);
              Tensor<1, 2>       normal({edge[1], -edge[0]});
              normal /= normal.norm();
              if ((face->center() - cell->center()) * normal < 0)
                normal = -normal;
              for (unsigned int v = 0; v < 2; ++v)
                {
                  local.push_back(face->vertex(v)[0]);
                  local.push_back(face->vertex(v)[1]);
                  local.push_back(face->vertex_dof_index(v, 0));
                  local.push_back(face->vertex_dof_index(v, 1));
                }
              local.push_back(normal[0]);
              local.push_back(normal[1]);
            }
    const auto gathered = Utilities::MPI::all_gather(
      dof_handler.get_triangulation().get_communicator(), local);

    // Nodes are identified by their x DoF, and numbered in lexicographic
    // order of their positions, so that the numbering does not depend on
    // the number of ranks.
    std::map<types::global_dof_index, Node> unique_nodes;
    std::vector<std::array<types::global_dof_index, 2>> segment_dofs;
    std::vector<Tensor<1, 2>>                             segment_normals;
    for (const auto &values : gathered)
      for (std::size_t i = 0; i < values.size(); i += 10)
        {
          std::array<types::global_dof_index, 2> ends;
          for (unsigned int v = 0; v < 2; ++v)
            {
              Node node;
              node.position = Point<2>(values[i + 4 * v], values[i + 4 * v + 1]);
              node.dofs     = {{static_cast<types::global_dof_index>(values[i + 4 * v + 2]),
                                static_cast<types::global_dof_index>(values[i + 4 * v + 3])}};
              ends[v]       = node.dofs[0];
              unique_nodes.emplace(node.dofs[0], node);
            }
          segment_dofs.push_back(ends);
          segment_normals.emplace_back(
            Tensor<1, 2>({values[i + 8], values[i + 9]}));
        }

    nodes.clear();
    for (const auto &[dof, node] : unique_nodes)
      nodes.push_back(node);
    std::sort(nodes.begin(), nodes.end(), [](const Node &a, const Node &b) {
      return a.position[0] < b.position[0] ||
             (a.position[0] == b.position[0] && a.position[1] < b.position[1]);
    });
    std::map<types::global_dof_index, unsigned int> index_of;
    for (unsigned int n = 0; n < nodes.size(); ++n)
      index_of[nodes[n].dofs[0]] = n;

    segments.clear();
    for (unsigned int s = 0; s < segment_dofs.size(); ++s)
      segments.push_back({{{index_of[segment_dofs[s][0]],
                            index_of[segment_dofs[s][1]]}},
                          segment_normals[s]});
    // Segments in the order of their first node, for reproducible sums.
    std::sort(segments.begin(), segments.end(),
              [](const Segment &a, const Segment &b) {
                return std::min(a.nodes[0], a.nodes[1]) <
                       std::min(b.nodes[0], b.nodes[1]);
              });

    // Nodal normals: the average of the adjacent segments' normals.
    for (auto &node : nodes)
      node.normal = Tensor<1, 2>();
    for (const auto &segment : segments)
      for (const unsigned int n : segment.nodes)
        nodes[n].normal += segment.normal;
    for (auto &node : nodes)
      {
        node.normal /= node.normal.norm();
        node.tangent = Tensor<1, 2>({-node.normal[1], node.normal[0]});
      }
  }



  void
  MortarInterface::reinit(const ElasticBody &slave_body,
                          const ElasticBody &master_body)
  {
    collect_contact_boundary(slave_body, slave, slave_segments);
    collect_contact_boundary(master_body, master, master_segments);

    D.assign(slave.size(), 0.);
    M.assign(slave.size(), {});
    gaps.assign(slave.size(), 0.);

    // D is diagonal with the dual basis: int psi_a phi_a = h / 2 on each
    // adjacent segment.
    for (const auto &segment : slave_segments)
      {
        const double h = slave[segment.nodes[0]].position.distance(
          slave[segment.nodes[1]].position);
        for (const unsigned int n : segment.nodes)
          D[n] += h / 2;
      }

    for (const auto &slave_segment : slave_segments)
      for (const auto &master_segment : master_segments)
        // Only segments that face each other can come into contact.
        if (slave_segment.normal * master_segment.normal < 0)
          integrate_segment_pair(slave_segment, master_segment);
  }



  void
  MortarInterface::integrate_segment_pair(const Segment &slave_segment,
                                          const Segment &master_segment)
  {
    const Point<2> &   a = slave[slave_segment.nodes[0]].position;
    const Point<2> &   b = slave[slave_segment.nodes[1]].position;
    const Point<2> &   c = master[master_segment.nodes[0]].position;
    const Point<2> &   d = master[master_segment.nodes[1]].position;
    const Tensor<1, 2> ab = b - a;
    const double       h  = ab.norm();
    const Tensor<1, 2> n  = slave_segment.normal;

    // The master segment's ends projected onto the slave segment (along
    // n, i.e. orthogonally), in the slave parameter xi in [0, 1].
    const double xi_c  = (c - a) * ab / (h * h);
    const double xi_d  = (d - a) * ab / (h * h);
    const double begin = std::max(0., std::min(xi_c, xi_d));
    const double end   = std::min(1., std::max(xi_c, xi_d));
    if (end - begin <= 1e-12)
      return;

    // Project x + t n = c + eta (d - c) for eta and t (the gap).
    const Tensor<1, 2> cd  = d - c;
    const double       det = -cd[0] * n[1] + cd[1] * n[0];
    if (std::abs(det) < 1e-12 * cd.norm())
      return;

    const QGauss<1> gauss(3);
    for (unsigned int q = 0; q < gauss.size(); ++q)
      {
        const double   xi = begin + (end - begin) * gauss.point(q)[0];
        const double   w  = gauss.weight(q) * (end - begin) * h;
        const Point<2> x  = a + xi * ab;
        const Tensor<1, 2> r = x - c;
        // Cramer's rule on [cd, -n] (eta, t)^T = r.
        const double eta = (-r[0] * n[1] + r[1] * n[0]) / det;
        const double t   = (cd[0] * r[1] - cd[1] * r[0]) / det;

        const double psi[2]      = {2 - 3 * xi, 3 * xi - 1};
        const double phi_m[2]    = {1 - eta, eta};
        for (unsigned int i = 0; i < 2; ++i)
          {
            const unsigned int j = slave_segment.nodes[i];
            for (unsigned int k = 0; k < 2; ++k)
              M[j][master_segment.nodes[k]] += psi[i] * phi_m[k] * w;
            gaps[j] += psi[i] * t * w;
          }
      }
  }



  bool
  MortarInterface::is_covered(const unsigned int j) const
  {
    double row_sum = 0;
    for (const auto &[l, m] : M[j])
      row_sum += m;
    return std::abs(row_sum - D[j]) <= 1e-8 * D[j];
  }



  std::vector<Tensor<1, 2>>
  MortarInterface::weighted_jump(
    const std::vector<Tensor<1, 2>> &slave_displacements,
    const std::vector<Tensor<1, 2>> &master_displacements) const
  {
    std::vector<Tensor<1, 2>> jump(slave.size());
    for (unsigned int j = 0; j < slave.size(); ++j)
      {
        jump[j] = D[j] * slave_displacements[j];
        for (const auto &[l, m] : M[j])
          jump[j] -= m * master_displacements[l];
      }
    return jump;
  }



  const std::vector<MortarInterface::Node> &
  MortarInterface::slave_nodes() const
  {
    return slave;
  }
  const std::vector<MortarInterface::Node> &
  MortarInterface::master_nodes() const
  {
    return master;
  }
  const std::vector<double> &
  MortarInterface::slave_weights() const
  {
    return D;
  }
  const std::vector<std::map<unsigned int, double>> &
  MortarInterface::master_coupling() const
  {
    return M;
  }
  const std::vector<double> &
  MortarInterface::weighted_initial_gaps() const
  {
    return gaps;
  }
} // namespace coulomb_adapt
