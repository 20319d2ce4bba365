#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>

#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/contact/segment_curve.h>

#include <algorithm>
#include <cmath>
#include <limits>

// The second half of the mortar interface: the integrals of D, M and g~
// on the segments that mortar_contact_boundary.cc collects, and what is
// measured with them (overlap quadrature, nodal gaps).

namespace coulomb_adapt
{
  namespace
  {
    using namespace mortar;

    // The slave point x(xi) projected onto the master curve along the
    // slave curve's normal: the master parameter eta and the distance t,
    // starting from the chord's solution.
    std::pair<double, double>
    project_onto_master(const SegmentCurve             &x,
                        const SegmentCurve             &y,
                        const MortarInterface::Segment &slave_segment,
                        const double                    xi)
    {
      const Point<2>     p   = x.value(xi);
      const Tensor<1, 2> n   = x.normal(xi, slave_segment.normal);
      const Tensor<1, 2> cd  = y.points[1] - y.points[0];
      const Tensor<1, 2> r   = p - y.points[0];
      const double       det = -cd[0] * n[1] + cd[1] * n[0];
      const double       eta = (-r[0] * n[1] + r[1] * n[0]) / det;
      return intersect_along(y, p, n, eta);
    }

    // cos(60 degrees): the least |n_s . n_m| of segments paired as facing
    // each other (reinit()).
    constexpr double facing_cosine = 0.5;



    // The distance of point p from the chord a-b.
    double
    distance_from_chord(const Point<2> &p, const Point<2> &a, const Point<2> &b)
    {
      const Tensor<1, 2> ab     = b - a;
      const double       length = ab.norm_square();
      const double       t =
        length > 0 ? std::clamp((p - a) * ab / length, 0., 1.) : 0.;
      return p.distance(a + t * ab);
    }



    // How near two segments' chords (ends) come, and the slave end
    // nearest to the master chord: chords that do not cross are nearest
    // at an end of one of them.
    std::pair<double, Point<2>>
    segment_distance(const std::vector<MortarInterface::Node> &slave_nodes,
                     const MortarInterface::Segment           &slave_segment,
                     const std::vector<MortarInterface::Node> &master_nodes,
                     const MortarInterface::Segment           &master_segment)
    {
      const Point<2> &a        = slave_nodes[slave_segment.nodes[0]].position;
      const Point<2> &b        = slave_nodes[slave_segment.nodes[1]].position;
      const Point<2> &c        = master_nodes[master_segment.nodes[0]].position;
      const Point<2> &d        = master_nodes[master_segment.nodes[1]].position;
      const double    from_a   = distance_from_chord(a, c, d);
      const double    from_b   = distance_from_chord(b, c, d);
      const double    distance = std::min({from_a,
                                           from_b,
                                           distance_from_chord(c, a, b),
                                           distance_from_chord(d, a, b)});
      return {distance, from_a <= from_b ? a : b};
    }



    // Degree 1: a segment's geometry for the initial gap, the circle
    // through its ends and its manifold midpoint where the manifold is
    // curved (the manifold's circle itself), else its chord.
    struct GapGeometry
    {
      bool     curved;
      Point<2> a, b, centre;
      double   radius;
    };

    GapGeometry
    gap_geometry(const std::vector<MortarInterface::Node> &nodes,
                 const MortarInterface::Segment           &segment)
    {
      const Point<2> &a = nodes[segment.nodes[0]].position,
                     &b = nodes[segment.nodes[1]].position;
      if (!segment.on_curved_manifold)
        return {false, a, b, Point<2>(), 0.};
      // The circumcentre of a, b and the manifold midpoint m.
      const Tensor<1, 2> u = b - a, v = segment.manifold_middle - a;
      const double       d = 2 * (u[0] * v[1] - u[1] * v[0]);
      const Point<2>     centre =
        a +
        Tensor<1, 2>({(v[1] * u.norm_square() - u[1] * v.norm_square()) / d,
                      (u[0] * v.norm_square() - v[0] * u.norm_square()) / d});
      return {true, a, b, centre, centre.distance(a)};
    }

    // The initial gap at the slave chord's point x: x moved radially onto
    // the slave circle, and the distance along the circle's normal there
    // to the master circle (or chord); the root of |X + t n - C| = R
    // nearer to X.
    double
    initial_gap_on_curves(const GapGeometry  &slave,
                          const GapGeometry  &master,
                          const Tensor<1, 2> &outward,
                          const Point<2>     &x)
    {
      Point<2>     X = x;
      Tensor<1, 2> n = outward;
      if (slave.curved)
        {
          n = (x - slave.centre) / (x - slave.centre).norm();
          X = slave.centre + slave.radius * n;
          if (n * outward < 0)
            n = -n;
        }
      if (!master.curved)
        {
          const Tensor<1, 2> cd = master.b - master.a, r = X - master.a;
          return (cd[0] * r[1] - cd[1] * r[0]) / (-cd[0] * n[1] + cd[1] * n[0]);
        }
      const Tensor<1, 2> q  = X - master.centre;
      const double       qn = q * n;
      const double       discriminant =
        qn * qn - q.norm_square() + master.radius * master.radius;
      const double root = std::sqrt(std::max(discriminant, 0.));
      return std::abs(-qn + root) < std::abs(-qn - root) ? -qn + root :
                                                           -qn - root;
    }



    // A Gauss rule fine enough for the length element |x'(xi)| of a curved
    // segment (not a polynomial): the row sums of M then equal D to round
    // off, as on straight segments.
    const QGauss<1> &
    curved_segment_quadrature()
    {
      static const QGauss<1> gauss(8);
      return gauss;
    }

    // int_segment phi_i / h: the diagonal of D on one segment.
    std::vector<double>
    segment_weights(const unsigned int degree)
    {
      if (degree == 1)
        return {1. / 2, 1. / 2};
      return {1. / 6, 1. / 6, 2. / 3};
    }

    // Wohlmuth's dual basis psi_i = sum_k A_ik phi_k, biorthogonal to the
    // phi: int psi_i phi_k = delta_ik int phi_k. A = D_e M_e^-1 with the
    // segment's mass matrix M_e and D_e = diag(int phi_i). For degree 1
    // this is psi_a = 2 phi_a - phi_b.
    FullMatrix<double>
    dual_basis_coefficients(const unsigned int degree)
    {
      const unsigned int n = degree + 1;
      FullMatrix<double> mass(n, n);
      const QGauss<1>    gauss(degree + 1);
      for (unsigned int q = 0; q < gauss.size(); ++q)
        {
          const auto phi = segment_shape_values(degree, gauss.point(q)[0]);
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int k = 0; k < n; ++k)
              mass(i, k) += phi[i] * phi[k] * gauss.weight(q);
        }
      FullMatrix<double> inverse(n, n);
      inverse.invert(mass);
      const auto         w = segment_weights(degree);
      FullMatrix<double> A(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int k = 0; k < n; ++k)
          A(i, k) = w[i] * inverse(i, k);
      return A;
    }
  } // namespace


  void
  MortarInterface::reinit(const ElasticBody &slave_body,
                          const ElasticBody &master_body)
  {
    slave_degree = collect_contact_boundary(slave_body, slave, slave_segments);
    master_degree =
      collect_contact_boundary(master_body, master, master_segments);
    dual_coefficients = dual_basis_coefficients(slave_degree);

    D.assign(slave.size(), 0.);
    M.assign(slave.size(), {});
    gaps.assign(slave.size(), 0.);
    overlap_list.clear();

    // D is diagonal with the dual basis: D_jj = int phi_j (h / 2 at a
    // vertex of a linear segment; h / 6 at a vertex and 2 h / 3 at the
    // middle node of a quadratic one).
    // On a curved segment with its length element J = |x'(xi)|:
    // D_jj = int phi_j J, and the dual basis is A_e = D_e M_e^-1 with the
    // segment's own mass matrix M_e = int phi_i phi_k J, so that psi and
    // phi stay biorthogonal on the curve.
    const auto weights = segment_weights(slave_degree);
    curved_dual_coefficients.assign(slave_segments.size(),
                                    FullMatrix<double>());
    for (unsigned int s = 0; s < slave_segments.size(); ++s)
      {
        const Segment &segment = slave_segments[s];
        if (segment.curved)
          {
            const SegmentCurve curve =
              segment_curve(slave, segment, slave_degree);
            const unsigned int n = segment.nodes.size();
            FullMatrix<double> mass(n, n), inverse(n, n),
              &A = curved_dual_coefficients[s];
            std::vector<double> integral(n, 0.);
            const auto         &gauss = curved_segment_quadrature();
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const double xi = gauss.point(q)[0];
                const double JxW =
                  curve.derivative(xi).norm() * gauss.weight(q);
                const auto phi = segment_shape_values(slave_degree, xi);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    integral[i] += phi[i] * JxW;
                    for (unsigned int k = 0; k < n; ++k)
                      mass(i, k) += phi[i] * phi[k] * JxW;
                  }
              }
            inverse.invert(mass);
            A.reinit(n, n);
            for (unsigned int i = 0; i < n; ++i)
              {
                D[segment.nodes[i]] += integral[i];
                for (unsigned int k = 0; k < n; ++k)
                  A(i, k) = integral[i] * inverse(i, k);
              }
            continue;
          }
        const double h = slave[segment.nodes[0]].position.distance(
          slave[segment.nodes[1]].position);
        for (unsigned int i = 0; i < segment.nodes.size(); ++i)
          D[segment.nodes[i]] += weights[i] * h;
      }

    // Only segments that face each other can come into contact: in small
    // deformations their normals stay nearly opposite where they touch.
    // Pairs at more than 60 degrees from opposite are left out: there the
    // gap along the slave normal grows like 1 / cos of the angle across a
    // segment, and the dual basis (psi_j = 2 phi_j - phi_k on P1) turns
    // so steep a gap into a weighted gap of either sign. A disc of
    // radius 10 mm on a block 200 mm wide (hertz) had its flanks' steep
    // segments covered by the block's far ends, weighted gaps of -34 mm
    // at two flank nodes, the contact there and epsilon = 2867 %;
    // accepting any angle below 90 degrees, as before, only worked where
    // the block ended before the flanks faced it.
    // The pairs left out by their angle are remembered where they touch,
    // for the diagnosis of a body that nothing faces (a sharp wedge).
    nearest_steep_contact.reset();
    double nearest_distance = std::numeric_limits<double>::max();
    for (unsigned int s = 0; s < slave_segments.size(); ++s)
      for (unsigned int m = 0; m < master_segments.size(); ++m)
        {
          const double cosine =
            slave_segments[s].normal * master_segments[m].normal;
          if (cosine < -facing_cosine)
            integrate_segment_pair(s, m);
          else if (cosine < 0)
            {
              const auto [distance, position] = segment_distance(
                slave, slave_segments[s], master, master_segments[m]);
              const double length =
                slave[slave_segments[s].nodes[0]].position.distance(
                  slave[slave_segments[s].nodes[1]].position);
              if (distance <= length && distance < nearest_distance)
                {
                  nearest_distance = distance;
                  nearest_steep_contact =
                    SteepContact{position,
                                 std::acos(-cosine) * 180. / numbers::PI};
                }
            }
        }
  }



  const std::optional<MortarInterface::SteepContact> &
  MortarInterface::steep_contact() const
  {
    return nearest_steep_contact;
  }



  void
  MortarInterface::integrate_segment_pair(const unsigned int slave_index,
                                          const unsigned int master_index)
  {
    const Segment &slave_segment  = slave_segments[slave_index];
    const Segment &master_segment = master_segments[master_index];
    if (slave_segment.curved || master_segment.curved)
      {
        integrate_curved_segment_pair(slave_index, master_index);
        return;
      }
    const Point<2>    &a  = slave[slave_segment.nodes[0]].position;
    const Point<2>    &b  = slave[slave_segment.nodes[1]].position;
    const Point<2>    &c  = master[master_segment.nodes[0]].position;
    const Point<2>    &d  = master[master_segment.nodes[1]].position;
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
    overlap_list.push_back({slave_index, master_index, begin, end});

    // The initial gap on the manifolds' curves where a P1 face lies on one
    // (Segment::on_curved_manifold), else on the chords.
    const bool on_curves =
      slave_segment.on_curved_manifold || master_segment.on_curved_manifold;
    const GapGeometry slave_geometry  = gap_geometry(slave, slave_segment);
    const GapGeometry master_geometry = gap_geometry(master, master_segment);

    // Exact for the products of the (dual) slave and master shape
    // functions on straight segments.
    const QGauss<1>     gauss(std::max(slave_degree, master_degree) + 2);
    const unsigned int  n_slave_nodes = slave_segment.nodes.size();
    std::vector<double> psi(n_slave_nodes);
    for (unsigned int q = 0; q < gauss.size(); ++q)
      {
        const double       xi = begin + (end - begin) * gauss.point(q)[0];
        const double       w  = gauss.weight(q) * (end - begin) * h;
        const Point<2>     x  = a + xi * ab;
        const Tensor<1, 2> r  = x - c;
        // Cramer's rule on [cd, -n] (eta, t)^T = r.
        const double eta = (-r[0] * n[1] + r[1] * n[0]) / det;
        const double t =
          on_curves ?
            initial_gap_on_curves(slave_geometry, master_geometry, n, x) :
            (cd[0] * r[1] - cd[1] * r[0]) / det;

        const auto phi_s = segment_shape_values(slave_degree, xi);
        const auto phi_m = segment_shape_values(master_degree, eta);
        for (unsigned int i = 0; i < n_slave_nodes; ++i)
          {
            psi[i] = 0;
            for (unsigned int k = 0; k < n_slave_nodes; ++k)
              psi[i] += dual_coefficients(i, k) * phi_s[k];
          }
        for (unsigned int i = 0; i < n_slave_nodes; ++i)
          {
            const unsigned int j = slave_segment.nodes[i];
            for (unsigned int k = 0; k < phi_m.size(); ++k)
              M[j][master_segment.nodes[k]] += psi[i] * phi_m[k] * w;
            gaps[j] += psi[i] * t * w;
          }
      }
  }



  // The same on the curves of the segments: the master segment's ends
  // projected orthogonally onto the slave curve give the overlap; a slave
  // point x(xi) is projected onto the master curve along the slave
  // curve's normal n(xi), the gap t the distance along it; the weights
  // carry the length element |x'(xi)|.
  void
  MortarInterface::integrate_curved_segment_pair(
    const unsigned int slave_index,
    const unsigned int master_index)
  {
    const Segment     &slave_segment  = slave_segments[slave_index];
    const Segment     &master_segment = master_segments[master_index];
    const SegmentCurve x = segment_curve(slave, slave_segment, slave_degree);
    const SegmentCurve y = segment_curve(master, master_segment, master_degree);
    const double       xi_c  = x.orthogonal_projection(y.points[0]);
    const double       xi_d  = x.orthogonal_projection(y.points[1]);
    const double       begin = std::max(0., std::min(xi_c, xi_d));
    const double       end   = std::min(1., std::max(xi_c, xi_d));
    if (end - begin <= 1e-12)
      return;
    // A master chord along the slave normal faces nothing (as on chords).
    const Tensor<1, 2> cd = y.points[1] - y.points[0];
    const Tensor<1, 2> n  = slave_segment.normal;
    if (std::abs(-cd[0] * n[1] + cd[1] * n[0]) < 1e-12 * cd.norm())
      return;
    overlap_list.push_back({slave_index, master_index, begin, end});

    const FullMatrix<double> &A = slave_segment.curved ?
                                    curved_dual_coefficients[slave_index] :
                                    dual_coefficients;
    const QGauss<1>           gauss(std::max(slave_degree, master_degree) + 4);
    const unsigned int        n_slave_nodes = slave_segment.nodes.size();
    std::vector<double>       psi(n_slave_nodes);
    for (unsigned int q = 0; q < gauss.size(); ++q)
      {
        const double xi     = begin + (end - begin) * gauss.point(q)[0];
        const auto [eta, t] = project_onto_master(x, y, slave_segment, xi);
        const double w =
          gauss.weight(q) * (end - begin) * x.derivative(xi).norm();
        const auto phi_s = segment_shape_values(slave_degree, xi);
        const auto phi_m = segment_shape_values(master_degree, eta);
        for (unsigned int i = 0; i < n_slave_nodes; ++i)
          {
            psi[i] = 0;
            for (unsigned int k = 0; k < n_slave_nodes; ++k)
              psi[i] += A(i, k) * phi_s[k];
          }
        for (unsigned int i = 0; i < n_slave_nodes; ++i)
          {
            const unsigned int j = slave_segment.nodes[i];
            for (unsigned int k = 0; k < phi_m.size(); ++k)
              M[j][master_segment.nodes[k]] += psi[i] * phi_m[k] * w;
            gaps[j] += psi[i] * t * w;
          }
      }
  }



  std::vector<double>
  MortarInterface::master_shape_values(const double eta) const
  {
    return segment_shape_values(master_degree, eta);
  }



  std::vector<MortarInterface::OverlapPoint>
  MortarInterface::overlap_quadrature(const unsigned int n_points) const
  {
    return overlap_quadrature(QGauss<1>(n_points));
  }



  std::vector<MortarInterface::OverlapPoint>
  MortarInterface::overlap_quadrature(const Quadrature<1> &gauss) const
  {
    std::vector<OverlapPoint> points;
    points.reserve(overlap_list.size() * gauss.size());
    for (unsigned int o = 0; o < overlap_list.size(); ++o)
      for (unsigned int q = 0; q < gauss.size(); ++q)
        points.push_back(overlap_point(o, gauss.point(q)[0], gauss.weight(q)));
    return points;
  }



  bool
  MortarInterface::overlap_is_straight(const unsigned int o) const
  {
    return !slave_segments[overlap_list[o].slave_segment].curved &&
           !master_segments[overlap_list[o].master_segment].curved;
  }



  MortarInterface::OverlapPoint
  MortarInterface::overlap_point(const unsigned int o,
                                 const double       t,
                                 const double       weight) const
  {
    const Overlap &overlap = overlap_list[o];
    const Segment &s_seg   = slave_segments[overlap.slave_segment];
    const Segment &m_seg   = master_segments[overlap.master_segment];
    const double   xi      = overlap.begin + (overlap.end - overlap.begin) * t;
    if (s_seg.curved || m_seg.curved)
      {
        const SegmentCurve x   = segment_curve(slave, s_seg, slave_degree);
        const SegmentCurve y   = segment_curve(master, m_seg, master_degree);
        const double       eta = project_onto_master(x, y, s_seg, xi).first;
        return {o,
                xi,
                eta,
                x.value(xi),
                y.value(eta),
                weight * (overlap.end - overlap.begin) *
                  x.derivative(xi).norm()};
      }
    const Point<2>    &a   = slave[s_seg.nodes[0]].position;
    const Point<2>    &b   = slave[s_seg.nodes[1]].position;
    const Point<2>    &c   = master[m_seg.nodes[0]].position;
    const Point<2>    &d   = master[m_seg.nodes[1]].position;
    const Tensor<1, 2> n   = s_seg.normal;
    const Tensor<1, 2> cd  = d - c;
    const double       det = -cd[0] * n[1] + cd[1] * n[0];
    const Point<2>     x   = a + xi * (b - a);
    const Tensor<1, 2> r   = x - c;
    const double       eta = (-r[0] * n[1] + r[1] * n[0]) / det;
    return {o,
            xi,
            eta,
            x,
            c + eta * cd,
            weight * (overlap.end - overlap.begin) * (b - a).norm()};
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



  std::vector<MortarInterface::NodalGap>
  MortarInterface::nodal_gaps(
    const TrilinosWrappers::MPI::Vector &slave_solution,
    const TrilinosWrappers::MPI::Vector &master_solution) const
  {
    const auto jump =
      weighted_jump(gather_nodal_displacements(slave, slave_solution),
                    gather_nodal_displacements(master, master_solution));
    std::vector<NodalGap> result(slave.size(), NodalGap{0., 0.});
    for (unsigned int j = 0; j < slave.size(); ++j)
      if (is_covered(j))
        result[j] = {(gaps[j] - jump[j] * slave[j].normal) / D[j],
                     jump[j] * slave[j].tangent / D[j]};
    return result;
  }



  // Each rank packs the nodes whose DoFs it owns as [node, u_x, u_y].
  std::vector<Tensor<1, 2>>
  MortarInterface::gather_nodal_displacements(
    const std::vector<Node>             &nodes,
    const TrilinosWrappers::MPI::Vector &u)
  {
    const IndexSet      owned = u.locally_owned_elements();
    std::vector<double> packed;
    for (unsigned int n = 0; n < nodes.size(); ++n)
      if (owned.is_element(nodes[n].dofs[0]))
        packed.insert(packed.end(),
                      {double(n), u(nodes[n].dofs[0]), u(nodes[n].dofs[1])});
    std::vector<Tensor<1, 2>> values(nodes.size());
    for (const auto &v :
         Utilities::MPI::all_gather(u.get_mpi_communicator(), packed))
      for (std::size_t i = 0; i < v.size(); i += 3)
        values[static_cast<unsigned int>(v[i])] =
          Tensor<1, 2>({v[i + 1], v[i + 2]});
    return values;
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
  const std::vector<MortarInterface::Segment> &
  MortarInterface::slave_segment_list() const
  {
    return slave_segments;
  }
  const std::vector<MortarInterface::Segment> &
  MortarInterface::master_segment_list() const
  {
    return master_segments;
  }
  const std::vector<MortarInterface::Overlap> &
  MortarInterface::overlaps() const
  {
    return overlap_list;
  }
  unsigned int
  MortarInterface::slave_element_degree() const
  {
    return slave_degree;
  }
  std::vector<double>
  MortarInterface::slave_shape_values(const double xi) const
  {
    return segment_shape_values(slave_degree, xi);
  }
  std::vector<double>
  MortarInterface::slave_bernstein_values(const double xi) const
  {
    return segment_bernstein_values(slave_degree, xi);
  }
} // namespace coulomb_adapt
