// The opening of the CRE's kinematic side narrower than the judged cells
// (narrow_opening.h, doc/indicator.md section 4c), against what it must
// satisfy whatever the mesh.
//
// Patch scene, P1 triangles and Q1 quadrilaterals, non-matching interface
// (6 slave against 10 master cells along y = const, n = (0, -1), zero
// initial gap: g = u_s,y - u_m,y). The master (lower) body has the affine
// displacement u_m = (a x + b y, c x + e y), so its stress sigma_c is
// constant and S = int sigma_c : eps(delta) = int_{dP} (sigma_c n) . delta
// over the patch's boundary, where delta is the trace on the contact faces
// and 0 elsewhere (no traction-free face is in the patch): S equals
// (sigma_c n) . int delta ds along the trace, which the test integrates
// itself (delta is linear on each fine face). The slave's interface
// nodes sit 1e-5 mm above the master's surface but one in the middle,
// 2e-4 mm below it: U_c penetrates on the two slave segments around it.
// Checked:
// - the identity for S, to round-off;
// - coverage: the gap of U_c + delta at 2,001 points of every overlap is
//   >= 0 (to 1e-12 of the penetration), and it was < 0 before;
// - homogeneity: with every displacement (and the threshold) doubled,
//   b^2 and S are 4 times as large, to 1e-12;
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



  Result
  open_master(const testing::SceneInterface &interface, const double scale)
  {
    const MortarInterface &mortar  = interface.mortar;
    const MPI_Comm         comm    = MPI_COMM_WORLD;
    const auto             ghosted = [&](const ElasticBody &body) {
      return TrilinosWrappers::MPI::Vector(body.locally_owned_dof_set(),
                                           body.locally_relevant_dof_set(),
                                           comm);
    };
    const AffineDisplacement      u_m(scale);
    TrilinosWrappers::MPI::Vector master_owned(
      interface.master.locally_owned_dof_set(), comm);
    VectorTools::interpolate(interface.master.mapping(),
                             interface.master.dof_handler(),
                             u_m,
                             master_owned);
    TrilinosWrappers::MPI::Vector master = ghosted(interface.master);
    master                               = master_owned;

    // The middle slave node dips below the master's surface.
    const auto &slave_nodes = mortar.slave_nodes();
    double      x_min = 1e300, x_max = -1e300;
    for (const auto &node : slave_nodes)
      {
        x_min = std::min(x_min, node.position[0]);
        x_max = std::max(x_max, node.position[0]);
      }
    TrilinosWrappers::MPI::Vector slave_owned(
      interface.slave.locally_owned_dof_set(), comm);
    const IndexSet &owned = interface.slave.locally_owned_dof_set();
    for (const auto &node : slave_nodes)
      {
        const bool middle =
          std::abs(node.position[0] - (x_min + x_max) / 2) < 1e-9 * x_max;
        const double above = scale * (middle ? -2e-4 : 1e-5);
        for (unsigned int c = 0; c < 2; ++c)
          if (owned.is_element(node.dofs[c]))
            slave_owned(node.dofs[c]) = c == 0 ?
                                          u_m.value(node.position, 0) :
                                          u_m.value(node.position, 1) + above;
      }
    slave_owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector slave = ghosted(interface.slave);
    slave                               = slave_owned;

    const std::array<const ElasticBody *, 2> bodies = {
      {&interface.slave, &interface.master}};
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> displacements = {
      {&slave, &master}};
    const auto slave_values =
      MortarInterface::gather_nodal_displacements(slave_nodes, slave);
    const auto master_values =
      MortarInterface::gather_nodal_displacements(mortar.master_nodes(),
                                                  master);
    std::vector<MortarInterface::OverlapPoint> dense;
    for (unsigned int o = 0; o < mortar.overlaps().size(); ++o)
      for (unsigned int k = 0; k <= 2000; ++k)
        dense.push_back(mortar.overlap_point(o, k / 2000., 0.));
    const std::vector<double> gaps =
      pointwise_gaps(mortar, dense, slave_values, master_values);
    const double penetration = -*std::min_element(gaps.begin(), gaps.end());
    AssertThrow(penetration > 1.9e-4 * scale,
                ExcMessage("U_c does not penetrate as set up"));

    const auto opening =
      make_narrow_opening(mortar, bodies, displacements, 1, 1e-2 * penetration);
    AssertThrow(opening.has_value(), ExcMessage("no narrow opening"));

    double lowest = 1e300;
    for (unsigned int k = 0; k < dense.size(); ++k)
      lowest = std::min(lowest, gaps[k] + opening->rise(mortar, dense[k]));
    AssertThrow(lowest >= -1e-12 * penetration,
                ExcMessage("U_c + delta penetrates by " +
                           std::to_string(-lowest)));

    // S against (sigma_c n) . int delta ds along the trace.
    const ElasticMaterial &material = interface.master.material();
    SymmetricTensor<2, 2>  strain;
    strain[0][0] = scale * 2e-4;
    strain[1][1] = scale * -5e-4;
    strain[0][1] = scale * (-1e-4 - 3e-4) / 2;
    const Tensor<1, 2> traction =
      material.stress(strain) * Tensor<1, 2>({0., 1.});
    double      boundary_work = 0;
    const auto &nodes         = mortar.master_nodes();
    for (const auto &[segment, faces] : opening->trace)
      {
        const auto  &s = mortar.master_segment_list()[segment];
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
    return {opening->norm_squared,
            opening->work,
            penetration,
            opening->patch_cells,
            opening->fine_cells,
            opening->refinements};
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
    const Result once       = open_master(interface, 1);
    const Result twice      = open_master(interface, 2);
    const double b2_ratio   = twice.norm_squared / once.norm_squared;
    const double work_ratio = twice.work / once.work;
    auto         out        = testing::root_output();
    // In 1e-6 N/mm, above numdiff's absolute tolerance.
    out << (cell_type == "triangle" ? "P1 triangles" : "Q1 quadrilaterals")
        << ": penetration " << std::setprecision(6) << 1e3 * once.penetration
        << " um; master opened on " << once.patch_cells << " cells bisected "
        << once.refinements << " times (" << once.fine_cells
        << " fine cells); b^2 = " << std::setprecision(8)
        << 1e6 * once.norm_squared << "e-6 N/mm, S = " << 1e6 * once.work
        << "e-6 N/mm (= the trace's work under the constant stress, to "
           "1e-12); "
        << "no penetration left at 2,001 points per overlap; doubled: b^2 x "
        << std::setprecision(12) << b2_ratio << ", S x " << work_ratio
        << std::endl;
    AssertThrow(std::abs(b2_ratio - 4) < 4e-12 &&
                  std::abs(work_ratio - 4) < 4e-12,
                ExcMessage("not homogeneous of degree 2"));
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check("triangle");
  check("quadrilateral");
}
