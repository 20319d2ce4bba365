// Mortar integrals on non-matching interfaces (theory.md section 2):
//  - patch scene, 3 slave vs 10 master segments (quadrilaterals) and the
//    same split into triangles, degrees 1 and 2 (three-node segments with
//    the quadratic dual basis): sum_j D_jj = interface length; every row
//    of M sums to D_jj (the master basis is a partition of unity); M
//    reproduces linear master fields, (M u)_j = D_jj u(x_j); zero gap;
//    normals (0, -1);
//  - hertz: the weighted initial gap g~_j / D_jj equals the dual-weighted
//    mean of the disc's height above the block (measured on the circle,
//    not the chords): the height y_j at the node less the sag bump
//    4 xi (1 - xi) h^2 / (8 R) of its two segments weighted with
//    psi_j = 2 phi_j - phi_k, sum_k h_k^3 / (12 R (h_1 + h_2)); up to the
//    tilt of the normals (relative error (x/R)^2 / 2).

#include "mortar_test_utilities.h"

#include <cmath>

using namespace coulomb_adapt;

void
check_patch(const std::string &cell_type, const std::string &degree = "1")
{
  const testing::SceneInterface scene_interface(
    {{"Scene/Name", "patch"},
     {"Mesh/Cell type", cell_type},
     {"Finite elements/Polynomial degree", degree},
     {"Scene/Patch/Upper body subdivisions", "3, 2"},
     {"Scene/Patch/Lower body subdivisions", "10, 4"}});
  const MortarInterface &interface = scene_interface.mortar;

  const auto &nodes = interface.slave_nodes();
  const auto &D     = interface.slave_weights();
  const auto &M     = interface.master_coupling();
  const auto &gaps  = interface.weighted_initial_gaps();

  // A linear field on the master side.
  const auto u = [](const Point<2> &x) {
    return Tensor<1, 2>({0.3 + 0.01 * x[0] - 0.02 * x[1], -0.2 + 0.02 * x[0]});
  };
  std::vector<Tensor<1, 2>> master_u, slave_zero(nodes.size());
  for (const auto &node : interface.master_nodes())
    master_u.push_back(u(node.position));
  const auto jump = interface.weighted_jump(slave_zero, master_u);

  double sum_D = 0, row_error = 0, linear_error = 0, gap_error = 0,
         normal_error = 0;
  for (unsigned int j = 0; j < nodes.size(); ++j)
    {
      sum_D += D[j];
      double row = 0;
      for (const auto &[l, m] : M[j])
        row += m;
      row_error    = std::max(row_error, std::abs(row - D[j]) / D[j]);
      linear_error = std::max(linear_error,
                              (-jump[j] - D[j] * u(nodes[j].position)).norm() /
                                (D[j] * u(nodes[j].position).norm()));
      gap_error    = std::max(gap_error, std::abs(gaps[j]) / D[j]);
      normal_error =
        std::max(normal_error,
                 (nodes[j].normal - Tensor<1, 2>({0., -1.})).norm());
    }
  auto out = testing::root_output();
  out << "patch (" << cell_type << ", degree " << degree
      << "): " << nodes.size() << " slave nodes, "
      << interface.master_nodes().size()
      << " master nodes, sum D = " << std::setprecision(12) << sum_D
      << std::endl;
  out << "  rows of M sum to D: " << (row_error < 1e-13 ? "yes" : "no")
      << "; M reproduces linear fields: "
      << (linear_error < 1e-13 ? "yes" : "no")
      << "; zero initial gap: " << (gap_error < 1e-13 ? "yes" : "no")
      << "; normals (0,-1): " << (normal_error < 1e-14 ? "yes" : "no")
      << std::endl;
  AssertThrow(std::abs(sum_D - 10.) < 1e-12, ExcMessage("sum of D"));
  AssertThrow(row_error < 1e-13 && linear_error < 1e-13 && gap_error < 1e-13 &&
                normal_error < 1e-14,
              ExcMessage("mortar integrals wrong: rows " +
                         std::to_string(row_error) + ", linear " +
                         std::to_string(linear_error) + ", gap " +
                         std::to_string(gap_error)));
}



void
check_hertz(const std::string &cell_type)
{
  const testing::SceneInterface scene_interface(
    {{"Scene/Name", "hertz"}, {"Mesh/Cell type", cell_type}});
  const MortarInterface &interface = scene_interface.mortar;

  const double R         = 100;
  const auto  &nodes     = interface.slave_nodes();
  unsigned int n_checked = 0;
  double       worst     = 0;
  auto         out       = testing::root_output();
  for (unsigned int j = 0; j < nodes.size(); ++j)
    {
      const Point<2> &x = nodes[j].position;
      if (std::abs(x[0]) > 5.)
        continue;
      const double gap =
        interface.weighted_initial_gaps()[j] / interface.slave_weights()[j];
      double sag = 0, length = 0;
      for (const auto &segment : interface.slave_segment_list())
        if (segment.nodes[0] == j || segment.nodes[1] == j)
          {
            const double h = nodes[segment.nodes[0]].position.distance(
              nodes[segment.nodes[1]].position);
            sag += h * h * h / (12 * R);
            length += h;
          }
      const double height = x[1] - sag / length;
      // Relative to the height, with an absolute floor for the node at 0.
      const double error = std::abs(gap - height) / std::max(x[1], 1e-6);
      worst              = std::max(worst, error);
      ++n_checked;
      AssertThrow(std::abs(gap - height) <= 2e-3 * x[1] + 1e-12 * R,
                  ExcMessage("gap at x = " + std::to_string(x[0]) + ": " +
                             std::to_string(gap) + " vs " +
                             std::to_string(height)));
    }
  out
    << "hertz (" << cell_type << "): " << n_checked
    << " slave nodes with |x| <= 5 mm, weighted gap = mean height on the circle within 2e-3: "
    << (worst <= 2e-3 ? "yes" : "no") << std::endl;
}



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_patch("quadrilateral");
  check_patch("triangle");
  check_patch("quadrilateral", "2");
  check_patch("triangle", "2");
  check_hertz("quadrilateral");
  check_hertz("triangle");
}
