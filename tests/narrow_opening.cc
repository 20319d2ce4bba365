// The opening of the CRE's kinematic side narrower than the judged cells
// (narrow_opening.h, doc/indicator.md section 4c), against what it must
// satisfy whatever the mesh.
//
// Patch scene, P1 triangles and Q1 quadrilaterals, non-matching interface
// (6 slave against 10 master cells along y = const, n = (0, -1), zero
// initial gap: g = u_s,y - u_m,y). Each body is opened in turn. The
// opened body has the affine displacement u = (a x + b y, c x + e y), so
// its stress sigma_c is constant and S = int sigma_c : eps(delta) =
// int_{dP} (sigma_c n) . delta over the patch's boundary, where delta is
// the trace on the contact faces and 0 elsewhere (no traction-free face
// is in the patch): S equals (sigma_c n) . int delta ds along the trace,
// which the test integrates itself (delta is linear on each fine face).
// The other body's interface nodes follow the opened body's surface,
// 1e-5 mm clear of it, but its middle node, 2e-4 mm into it: U_c
// penetrates on the two segments around it.
// Checked:
// - the identity for S, to round-off;
// - coverage, from the trace itself: the opened body moves into itself
//   (delta_y >= 0 on the upper, slave body, <= 0 on the lower), and
//   u_s,y - u_m,y with delta added is >= 0 (to 1e-12 of the penetration)
//   at 2,001 points of every overlap, where it was < 0 before; rise()
//   gives that same change of the gap;
// - homogeneity: with every displacement (and the threshold) doubled,
//   b^2 and S are 4 times as large, to 1e-12;
// - the judged cells' shares of b^2, each on the rank that owns the
//   cell, sum to b^2 (to 1e-12);
// - the same patch, b^2 and S on 1 and 2 ranks (the outputs).

#include <deal.II/base/function.h>

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/indicator/narrow_opening.h>
#include <coulomb_adapt/indicator/pointwise_gap.h>

#include "mortar_test_utilities.h"

#include <algorithm>
#include <cmath>

using namespace coulomb_adapt;

namespace
{
  class AffineDisplacement : public Function<2>
  {
  public:
    explicit AffineDisplacement(const double scale)
      : Function<2>(2)
      , scale(scale)
    {}
    double
    value(const Point<2> &p, const unsigned int component) const override
    {
      return scale * (component == 0 ? 2e-4 * p[0] - 1e-4 * p[1] :
                                       -3e-4 * p[0] - 5e-4 * p[1]);
    }
    const double scale;
  };



  struct Result
  {
    double       norm_squared, work, penetration;
    unsigned int patch_cells, fine_cells, refinements;
  };



  // The trace's delta at @p point of an overlap, on the opened @p side
  // (the interface is horizontal: the chord parameter from x alone).
  Tensor<1, 2>
  trace_at(const NarrowOpening                 &opening,
           const MortarInterface               &mortar,
           const unsigned int                   side,
           const MortarInterface::OverlapPoint &point)
  {
    const auto        &overlap = mortar.overlaps()[point.overlap];
    const unsigned int segment =
      side == 0 ? overlap.slave_segment : overlap.master_segment;
    const auto faces = opening.trace.find(segment);
    if (faces == opening.trace.end())
      return Tensor<1, 2>();
    const auto &nodes =
      side == 0 ? mortar.slave_nodes() : mortar.master_nodes();
    const auto &ends = (side == 0 ? mortar.slave_segment_list() :
                                    mortar.master_segment_list())[segment]
                         .nodes;
    const double x0  = nodes[ends[0]].position[0];
    const double x1  = nodes[ends[1]].position[0];
    const double x   = (side == 0 ? point.slave_point : point.master_point)[0];
    const double tau = (x - x0) / (x1 - x0);
    for (const auto &f : faces->second)
      if (tau >= f.begin - 1e-12 && tau <= f.end + 1e-12)
        {
          const double t = (tau - f.begin) / (f.end - f.begin);
          return (1 - t) * f.delta_begin + t * f.delta_end;
        }
    return Tensor<1, 2>();
  }



  Result
  open_side(const testing::SceneInterface &interface,
            const double                   scale,
            const unsigned int             side)
  {
    const MortarInterface &mortar  = interface.mortar;
    const MPI_Comm         comm    = MPI_COMM_WORLD;
    const auto             ghosted = [&](const ElasticBody &body) {
      return TrilinosWrappers::MPI::Vector(body.locally_owned_dof_set(),
                                           body.locally_relevant_dof_set(),
                                           comm);
    };
    const std::array<const ElasticBody *, 2> bodies = {
      {&interface.slave, &interface.master}};
    const ElasticBody            &opened = *bodies[side];
    const ElasticBody            &other  = *bodies[1 - side];
    const AffineDisplacement      u(scale);
    TrilinosWrappers::MPI::Vector opened_owned(opened.locally_owned_dof_set(),
                                               comm);
    VectorTools::interpolate(opened.mapping(),
                             opened.dof_handler(),
                             u,
                             opened_owned);

    // The other body's interface nodes 1e-5 mm clear of the opened
    // body's surface, its middle one 2e-4 mm into it (g = u_s,y - u_m,y:
    // the slave lies above).
    const auto &other_nodes =
      side == 0 ? mortar.master_nodes() : mortar.slave_nodes();
    double x_min = 1e300, x_max = -1e300;
    for (const auto &node : other_nodes)
      {
        x_min = std::min(x_min, node.position[0]);
        x_max = std::max(x_max, node.position[0]);
      }
    TrilinosWrappers::MPI::Vector other_owned(other.locally_owned_dof_set(),
                                              comm);
    const IndexSet               &owned    = other.locally_owned_dof_set();
    unsigned int                  n_middle = 0;
    for (const auto &node : other_nodes)
      {
        const bool middle =
          std::abs(node.position[0] - (x_min + x_max) / 2) < 1e-9 * x_max;
        n_middle += middle;
        const double clear = scale * (middle ? -2e-4 : 1e-5);
        for (unsigned int c = 0; c < 2; ++c)
          if (owned.is_element(node.dofs[c]))
            other_owned(node.dofs[c]) =
              c == 0 ? u.value(node.position, 0) :
                       u.value(node.position, 1) + (side == 1 ? clear : -clear);
      }
    AssertThrow(n_middle == 1, ExcMessage("no node in the middle"));
    other_owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector opened_u = ghosted(opened);
    opened_u                               = opened_owned;
    TrilinosWrappers::MPI::Vector other_u  = ghosted(other);
    other_u                                = other_owned;

    std::array<const TrilinosWrappers::MPI::Vector *, 2> displacements;
    displacements[side]     = &opened_u;
    displacements[1 - side] = &other_u;
    const auto slave_values =
      MortarInterface::gather_nodal_displacements(mortar.slave_nodes(),
                                                  *displacements[0]);
    const auto master_values =
      MortarInterface::gather_nodal_displacements(mortar.master_nodes(),
                                                  *displacements[1]);
    std::vector<MortarInterface::OverlapPoint> dense;
    for (unsigned int o = 0; o < mortar.overlaps().size(); ++o)
      for (unsigned int k = 0; k <= 2000; ++k)
        dense.push_back(mortar.overlap_point(o, k / 2000., 0.));
    const std::vector<double> gaps =
      pointwise_gaps(mortar, dense, slave_values, master_values);
    const double penetration = -*std::min_element(gaps.begin(), gaps.end());
    AssertThrow(penetration > 1.9e-4 * scale,
                ExcMessage("U_c does not penetrate as set up"));

    const auto opening = make_narrow_opening(
      mortar, bodies, displacements, side, 1e-2 * penetration);
    AssertThrow(opening.has_value(), ExcMessage("no narrow opening"));

    // Into its own body: the upper (slave) body up, the lower one down.
    const double inward = side == 0 ? 1. : -1.;
    for (const auto &[segment, faces] : opening->trace)
      for (const auto &f : faces)
        for (const auto &d : {f.delta_begin, f.delta_end})
          AssertThrow(inward * d[1] >= -1e-15 * penetration,
                      ExcMessage("the trace moves out of its body"));
    double lowest = 1e300, rise_mismatch = 0;
    for (unsigned int k = 0; k < dense.size(); ++k)
      {
        const double change =
          inward * trace_at(*opening, mortar, side, dense[k])[1];
        lowest = std::min(lowest, gaps[k] + change);
        rise_mismatch =
          std::max(rise_mismatch,
                   std::abs(opening->rise(mortar, dense[k]) - change));
      }
    AssertThrow(lowest >= -1e-12 * penetration,
                ExcMessage("U_c + delta penetrates by " +
                           std::to_string(-lowest)));
    AssertThrow(rise_mismatch <= 1e-12 * penetration,
                ExcMessage("rise() is not the trace's change of the gap"));

    // S against (sigma_c n) . int delta ds along the trace.
    const ElasticMaterial &material = opened.material();
    SymmetricTensor<2, 2>  strain;
    strain[0][0] = scale * 2e-4;
    strain[1][1] = scale * -5e-4;
    strain[0][1] = scale * (-1e-4 - 3e-4) / 2;
    // The opened body's outward normal: down for the upper (slave) body.
    const Tensor<1, 2> traction =
      material.stress(strain) * Tensor<1, 2>({0., -inward});
    double      boundary_work = 0;
    const auto &nodes =
      side == 0 ? mortar.slave_nodes() : mortar.master_nodes();
    for (const auto &[segment, faces] : opening->trace)
      {
        const auto  &s = (side == 0 ? mortar.slave_segment_list() :
                                      mortar.master_segment_list())[segment];
        const double length =
          (nodes[s.nodes[1]].position - nodes[s.nodes[0]].position).norm();
        for (const auto &f : faces)
          boundary_work += traction * (f.delta_begin + f.delta_end) / 2 *
                           (f.end - f.begin) * length;
      }
    AssertThrow(std::abs(opening->work - boundary_work) <=
                  1e-12 * std::abs(boundary_work),
                ExcMessage("S = " + std::to_string(opening->work) +
                           " but the trace's work is " +
                           std::to_string(boundary_work)));
    AssertThrow(opening->norm_squared > 0 && boundary_work != 0,
                ExcMessage("no opening"));
    // Each judged cell's share lands on the rank that owns it, once.
    const double cell_sum =
      Utilities::MPI::sum(opening->energy.l1_norm(), comm);
    AssertThrow(std::abs(cell_sum - opening->norm_squared) <=
                  1e-12 * opening->norm_squared,
                ExcMessage("the cells' b^2 do not sum to b^2"));
    return {opening->norm_squared,
            opening->work,
            penetration,
            opening->patch.cells,
            opening->patch.fine_cells,
            opening->patch.refinements};
  }



  void
  check(const std::string &cell_type)
  {
    const testing::SceneInterface interface(
      {{"Scene/Name", "patch"},
       {"Mesh/Cell type", cell_type},
       {"Finite elements/Polynomial degree", "1"},
       {"Scene/Patch/Upper body subdivisions", "6, 2"},
       {"Scene/Patch/Lower body subdivisions", "10, 4"}});
    for (const unsigned int side : {0u, 1u})
      {
        const Result once       = open_side(interface, 1, side);
        const Result twice      = open_side(interface, 2, side);
        const double b2_ratio   = twice.norm_squared / once.norm_squared;
        const double work_ratio = twice.work / once.work;
        auto         out        = testing::root_output();
        // In 1e-6 N/mm, above numdiff's absolute tolerance.
        out << (cell_type == "triangle" ? "P1 triangles" : "Q1 quadrilaterals")
            << ": penetration " << std::setprecision(6)
            << 1e3 * once.penetration << " um; "
            << (side == 0 ? "slave" : "master") << " opened on "
            << once.patch_cells << " cells bisected " << once.refinements
            << " times (" << once.fine_cells
            << " fine cells); b^2 = " << std::setprecision(8)
            << 1e6 * once.norm_squared << "e-6 N/mm, S = " << 1e6 * once.work
            << "e-6 N/mm (= the trace's work under the constant stress, to "
               "1e-12); "
            << "moved into itself, no penetration left at 2,001 points per "
               "overlap; doubled: b^2 x "
            << std::setprecision(12) << b2_ratio << ", S x " << work_ratio
            << std::endl;
        AssertThrow(std::abs(b2_ratio - 4) < 4e-12 &&
                      std::abs(work_ratio - 4) < 4e-12,
                    ExcMessage("not homogeneous of degree 2"));
      }
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check("triangle");
  check("quadrilateral");
}
