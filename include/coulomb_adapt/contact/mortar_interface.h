#ifndef coulomb_adapt_contact_mortar_interface_h
#define coulomb_adapt_contact_mortar_interface_h

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/cell_id.h>

#include <deal.II/lac/full_matrix.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/segment_curve.h>

#include <array>
#include <map>
#include <optional>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The mortar discretisation of the contact interface between the slave
   * body (body 1, the upper one) and the master body (body 2), theory.md
   * section 2, for elements of degree 1 (Q1 / P1: two-node segments) and
   * 2 (Q2 / P2: three-node segments, the middle node on the boundary's
   * manifold). A segment is its face as the element's mapping makes it:
   * straight for degree 1 and on flat boundaries (the integrals use the
   * chord), the parabola through its three nodes where the middle node
   * lies off the chord (a curved manifold; Segment::curved). On curved
   * segments the integrals carry the length element, the dual basis is
   * built from the segment's own mass matrix, master ends are projected
   * onto the slave curve orthogonally and slave points onto the master
   * curve along the slave curve's normal; nodal normals are the curves'
   * normals at the nodes. Degree 1 on a curved manifold keeps the
   * chords for everything but the initial gap g_0, which is measured
   * between the manifold's curves (Segment::on_curved_manifold).
   *
   * The Lagrange multiplier lives on the slave nodes with Wohlmuth's dual
   * basis (psi_a = 2 phi_a - phi_b on a linear slave segment [a, b]; for
   * quadratic segments psi = D_e M_e^-1 phi, which is well defined in 2D
   * because every quadratic shape function has a positive integral), so
   * that
   *
   *   D_jj = int psi_j phi_j = int phi_j        (diagonal)
   *   M_jl = int psi_j phi^2_l                  (master, on the overlaps)
   *   g~_j = int psi_j g_0                       (weighted initial gap)
   *
   * M and g~ are integrated segment to segment: the master segments are
   * projected onto each slave segment (orthogonally to it), and on the
   * overlap Gauss points of the slave segment are projected onto the master
   * segment along the slave segment's normal; g_0 is the distance along
   * that normal (>= 0: separated). Meshes need not match.
   *
   * The interface is small (a curve in 2D), so every rank gathers all of
   * it: each rank contributes the contact faces of its own cells.
   */
  class MortarInterface
  {
  public:
    /** A node of the slave or master contact boundary. */
    struct Node
    {
      Point<2> position;
      /** Global DoF indices of the x and y displacement at the node. */
      std::array<types::global_dof_index, 2> dofs;
      /** Slave nodes: averaged outward unit normal of the slave body, and
       * the tangent t = (-n_y, n_x). */
      Tensor<1, 2> normal;
      Tensor<1, 2> tangent;
    };

    /** A contact face of one side. */
    struct Segment
    {
      /** Indices into the node list of the same side: the two ends, then
       * (degree 2) the middle node. */
      std::vector<unsigned int> nodes;
      /** Outward unit normal of the body at this segment. */
      Tensor<1, 2> normal;
      /** The cell the face belongs to. */
      CellId cell;
      /** Degree 2 with the middle node off the chord's midpoint (on a
       * curved manifold): the segment is the parabola through its three
       * nodes, and the integrals are taken on it. */
      bool curved = false;
      /** Degree 1 with the boundary's manifold off the chord (a circle):
       * the manifold's point halfway along the face. The element is the
       * chord, which lies h^2 / (8 R) inside a circle of radius R at its
       * middle, more than the interference of a press fit; so the initial
       * gap g_0 (only it) is measured on the circle through the ends and
       * this point (the manifold's circle itself), so that nodes of the
       * two sides at different angles see the true distance of the
       * curves. */
      Point<2> manifold_middle;
      bool     on_curved_manifold = false;
    };

    /** Where a projected master segment overlaps a slave segment: the
     * parameter interval [begin, end] of the slave segment (its chord, or
     * its curve if curved; 0 at its first node, 1 at its second). */
    struct Overlap
    {
      unsigned int slave_segment;
      unsigned int master_segment;
      double       begin;
      double       end;
    };

    /** Collect both contact boundaries and integrate D, M and g~. */
    void
    reinit(const ElasticBody &slave, const ElasticBody &master);

    const std::vector<Node> &
    slave_nodes() const;
    const std::vector<Node> &
    master_nodes() const;

    /** D_jj for slave node j (mm). */
    const std::vector<double> &
    slave_weights() const;

    /** M_jl: for slave node j, the master nodes l it couples to (mm). */
    const std::vector<std::map<unsigned int, double>> &
    master_coupling() const;

    /** g~_j = int psi_j g_0 (mm^2). */
    const std::vector<double> &
    weighted_initial_gaps() const;

    const std::vector<Segment> &
    slave_segment_list() const;
    const std::vector<Segment> &
    master_segment_list() const;

    /** Every slave/master segment overlap, the pieces of the interface
     * where the two bodies face each other. */
    const std::vector<Overlap> &
    overlaps() const;

    /** Degree of the slave side's elements (1 or 2). */
    unsigned int
    slave_element_degree() const;

    /** Values of the slave segment's shape functions (ends, then middle
     * node) at parameter @p xi in [0, 1]. */
    std::vector<double>
    slave_shape_values(const double xi) const;

    /** Values of the slave segment's Bernstein polynomials (same order)
     * at @p xi: mortar::segment_bernstein_values(). */
    std::vector<double>
    slave_bernstein_values(const double xi) const;

    /** Values of the master segment's shape functions (ends, then middle
     * node) at parameter @p eta in [0, 1] of its chord. */
    std::vector<double>
    master_shape_values(const double eta) const;

    /** A Gauss point of an overlap: where a slave segment faces a master
     * segment. The slave point is projected onto the master segment along
     * the slave segment's normal, as in the integrals of M and g~ (chords,
     * or the curves of curved segments). */
    struct OverlapPoint
    {
      /** Index into overlaps(). */
      unsigned int overlap;
      /** Parameters on the slave and master chords, in [0, 1]. */
      double   xi;
      double   eta;
      Point<2> slave_point;
      Point<2> master_point;
      /** Gauss weight times the slave chord length, or the length
       * element of a curved slave segment (mm). */
      double weight;
    };

    /** @p n_points Gauss points on every overlap: a quadrature of the part of
     * the interface where the bodies face each other, exact for polynomials
     * of degree 2 n_points - 1 in the slave parameter. */
    std::vector<OverlapPoint>
    overlap_quadrature(const unsigned int n_points) const;

    /** The same with any quadrature of [0, 1] mapped onto every overlap
     * (Gauss-Lobatto: the overlap's ends included, where the gap of
     * linear segments is smallest). */
    std::vector<OverlapPoint>
    overlap_quadrature(const Quadrature<1> &quadrature) const;

    /** Whether overlap @p o faces a straight master segment from a
     * straight slave segment: the master parameter is then affine in the
     * slave parameter, and the gap of segments of degree p is a
     * polynomial of degree p along the overlap. */
    bool
    overlap_is_straight(const unsigned int o) const;

    /** The point at @p t in [0, 1] of overlap @p o, its weight @p weight
     * times the overlap's length element (what overlap_quadrature() makes
     * of each quadrature point). */
    OverlapPoint
    overlap_point(const unsigned int o,
                  const double       t,
                  const double       weight) const;

    /** Where the curves touch at more than 60 degrees from facing (a sharp
     * wedge's tip on a flat): the pairs reinit() leaves out by their
     * angle. */
    struct SteepContact
    {
      /** The slave segment's end nearest to the master segment. */
      Point<2> position;
      /** The angle between -n_slave and n_master, in degrees. */
      double angle;
    };
    /** Of the pairs left out by their angle (between 60 and 90 degrees
     * from facing), the one whose segments come nearest, if they come
     * within the slave segment's length of each other; else none. For the
     * diagnosis of a body that nothing faces. */
    const std::optional<SteepContact> &
    steep_contact() const;

    /** Whether the master surface covers slave node j's support
     * completely (sum_l M_jl = D_jj): only such nodes can come into
     * contact; the others lie beyond the master's edge. */
    bool
    is_covered(const unsigned int j) const;

    /** The weighted displacement jump (D u^1 - M u^2)_j at every slave
     * node, from nodal displacements (x, y) of the slave and master nodes. */
    std::vector<Tensor<1, 2>>
    weighted_jump(const std::vector<Tensor<1, 2>> &slave_displacements,
                  const std::vector<Tensor<1, 2>> &master_displacements) const;

    /** A slave node's normal gap and tangential jump (mm). */
    struct NodalGap
    {
      double gap;
      double slip;
    };
    /** At every slave node, from the bodies' displacements (distributed
     * vectors; every rank gets all nodes): the normal gap
     * (g~_j - n_j . (D u^1 - M u^2)_j) / D_jj and the tangential jump
     * t_j . (D u^1 - M u^2)_j / D_jj, both zero at nodes not covered by
     * the master side. The contact solver's iterates and the corrected
     * solution of the error indicator are measured with it. */
    std::vector<NodalGap>
    nodal_gaps(const TrilinosWrappers::MPI::Vector &slave_solution,
               const TrilinosWrappers::MPI::Vector &master_solution) const;

    /** The displacements at @p nodes (of either side) from a distributed
     * displacement vector, gathered on every rank. */
    static std::vector<Tensor<1, 2>>
    gather_nodal_displacements(const std::vector<Node>             &nodes,
                               const TrilinosWrappers::MPI::Vector &u);

  private:
    /** Returns the degree of the body's elements. */
    static unsigned int
    collect_contact_boundary(const ElasticBody    &body,
                             std::vector<Node>    &nodes,
                             std::vector<Segment> &segments);

    void
    integrate_segment_pair(const unsigned int slave_segment_index,
                           const unsigned int master_segment_index);
    void
    integrate_curved_segment_pair(const unsigned int slave_segment_index,
                                  const unsigned int master_segment_index);

    std::vector<Node>                           slave;
    std::vector<Node>                           master;
    std::vector<Segment>                        slave_segments;
    std::vector<Segment>                        master_segments;
    std::vector<double>                         D;
    std::vector<std::map<unsigned int, double>> M;
    std::vector<double>                         gaps;
    std::vector<Overlap>                        overlap_list;
    std::optional<SteepContact>                 nearest_steep_contact;
    unsigned int                                slave_degree  = 1;
    unsigned int                                master_degree = 1;
    /** Dual basis of the slave segments: psi_i = sum_k A_ik phi_k. */
    FullMatrix<double> dual_coefficients;
    /** The same per curved slave segment (empty for straight ones), from
     * the segment's own mass matrix with its length element. */
    std::vector<FullMatrix<double>> curved_dual_coefficients;
  };

  namespace mortar
  {
    /** The curve of a segment of either side through its nodes in @p nodes
     * (ends, then the middle node), for elements of degree @p degree. */
    SegmentCurve
    segment_curve(const std::vector<MortarInterface::Node> &nodes,
                  const MortarInterface::Segment           &segment,
                  const unsigned int                        degree);
  } // namespace mortar
} // namespace coulomb_adapt

#endif
