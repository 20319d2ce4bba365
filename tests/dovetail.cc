// The dovetail blade root of prm/dovetail.prm (prm/meshes/dovetail.geo: a
// steel blade, root 20 mm wide with 30 degree flanks, in a disc slot,
// omega = 1000 rad/s about an axis 300 mm below the root, mu = 0.5, P1
// triangles), on its first mesh, against truths that need no finite
// elements:
//  - global equilibrium: only the contact holds the blade, so the contact
//    force on it is minus its centrifugal force
//    rho omega^2 A (x_c - x_axis). A and the
//    centroid x_c are computed here twice, in closed form from the
//    polygon's corners (shoelace) and by quadrature over the blade's mesh;
//    the force to 1e-11 relative (measured 4e-14);
//  - symmetry: the mesh is mirror-symmetric about x = 0 (the .geo meshes
//    the left halves as the right halves' mirror images), so every node of
//    the left flank has its mirror node on the right with the same state,
//    the same pressure and the opposite tangential traction (to 1e-11 of
//    the largest pressure; measured 9e-13), and the two flanks carry
//    mirror forces (1e-11);
//  - the Coulomb cone: |lambda_t| <= mu p at every node, with equality at
//    the slip nodes (both to 1e-12 of the largest pressure: round-off);
//  - partial slip: each flank has stick and slip nodes.
// The 2-rank output is the same file: 1 and 2 ranks agree.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include "contact_test_utilities.h"
#include "dovetail_blade.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const double   rho = 7.85e-9, omega = 1000, mu = 0.5;
  const Point<2> axis(0, -300);

  // The blade's outline (dovetail.geo: flanks at 30 degrees), its area and
  // centroid in closed form.
  const DovetailBlade outline(numbers::PI / 6);
  const double        A        = outline.area;
  const Point<2>      centroid = outline.centroid;

  auto problem =
    testing::solve_contact({{"Scene/Gmsh/Mesh file",
                             testing::example_file("meshes/dovetail.geo")}},
                           testing::example_file("dovetail.prm"));
  const ElasticBody &blade = *problem->bodies[0];

  // The same by quadrature over the blade's mesh.
  double       A_mesh = 0;
  Tensor<1, 2> first_moment_mesh;
  {
    FEValues<2> fe_values(blade.mapping(),
                          blade.dof_handler().get_fe(),
                          blade.cell_quadrature(),
                          update_quadrature_points | update_JxW_values);
    for (const auto &cell : blade.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
            {
              A_mesh += fe_values.JxW(q);
              first_moment_mesh +=
                fe_values.JxW(q) * fe_values.quadrature_point(q);
            }
        }
    A_mesh = Utilities::MPI::sum(A_mesh, MPI_COMM_WORLD);
    for (unsigned int d = 0; d < 2; ++d)
      first_moment_mesh[d] =
        Utilities::MPI::sum(first_moment_mesh[d], MPI_COMM_WORLD);
  }
  const Point<2>     centroid_mesh(first_moment_mesh / A_mesh);
  const Tensor<1, 2> centrifugal = rho * omega * omega * A * (centroid - axis);

  out << std::setprecision(8) << "blade: area " << A << " mm^2, centroid ("
      << (std::abs(centroid[0]) < 1e-12 ? 0. : centroid[0]) << ", "
      << centroid[1] << ") mm; the mesh's within 1e-12: "
      << (std::abs(A_mesh / A - 1) < 1e-12 &&
              (centroid_mesh - centroid).norm() < 1e-12 * centroid.norm() ?
            "yes" :
            "no")
      << std::endl
      << "centrifugal force rho omega^2 A (x_c - x_axis) = ("
      << (std::abs(centrifugal[0]) < 1e-12 * centrifugal.norm() ?
            0. :
            centrifugal[0])
      << ", " << centrifugal[1] << ") N/mm" << std::endl;
  AssertThrow(std::abs(A_mesh / A - 1) < 1e-12 &&
                (centroid_mesh - centroid).norm() < 1e-12 * centroid.norm(),
              ExcMessage("the mesh is not the blade's outline"));

  const ContactSolverReport &report = problem->report;
  const double               equilibrium =
    (report.contact_force + centrifugal).norm() / centrifugal.norm();
  out << "contact force on the blade (" << std::setprecision(8)
      << (std::abs(report.contact_force[0]) < 1e-10 * centrifugal.norm() ?
            0. :
            report.contact_force[0])
      << ", " << report.contact_force[1]
      << ") N/mm: minus the centrifugal force to 1e-11: "
      << (equilibrium < 1e-11 ? "yes" : "no") << "; Newton steps in [1, 10]: "
      << (report.newton_iterations >= 1 && report.newton_iterations <= 10 ?
            "yes" :
            "no")
      << std::endl;
  AssertThrow(equilibrium < 1e-11,
              ExcMessage("equilibrium off by " + std::to_string(equilibrium)));
  AssertThrow(report.newton_iterations >= 1 && report.newton_iterations <= 10,
              ExcMessage("Newton steps out of range"));

  // Per flank (x < 0 left, x > 0 right): counts, force, and the cone.
  const auto                 &states = problem->solver->node_states();
  const double                p_max  = report.max_contact_pressure;
  double                      cone = 0, slip_on_cone = 0, mirror = 0;
  std::array<unsigned int, 2> n_stick{{0, 0}}, n_slip{{0, 0}}, n_open{{0, 0}};
  std::array<Tensor<1, 2>, 2> flank_force;
  std::array<double, 2>       lowest_stick{{1e9, 1e9}}, highest_slip{{0, 0}};
  for (const auto &s : states)
    {
      const unsigned int side = s.position[0] > 0;
      n_stick[side] += s.status == ContactStatus::stick;
      n_slip[side] += s.status == ContactStatus::slip;
      n_open[side] += s.status == ContactStatus::open;
      flank_force[side] +=
        -s.weight * (s.pressure * s.normal + s.tangential_traction * s.tangent);
      cone =
        std::max(cone,
                 (std::abs(s.tangential_traction) - mu * s.pressure) / p_max);
      if (s.status == ContactStatus::slip)
        {
          slip_on_cone       = std::max(slip_on_cone,
                                  std::abs(std::abs(s.tangential_traction) -
                                           mu * s.pressure) /
                                    p_max);
          highest_slip[side] = std::max(highest_slip[side], s.position[1]);
        }
      if (s.status == ContactStatus::stick)
        lowest_stick[side] = std::min(lowest_stick[side], s.position[1]);

      // The mirror node.
      const Point<2> image(-s.position[0], s.position[1]);
      const auto     m = std::find_if(states.begin(),
                                  states.end(),
                                  [&](const ContactNodeState &o) {
                                    return (o.position - image).norm() < 1e-9;
                                  });
      AssertThrow(m != states.end(),
                  ExcMessage("a slave node without its mirror node"));
      AssertThrow(m->status == s.status,
                  ExcMessage("mirror nodes in different states"));
      mirror = std::max(
        {mirror,
         std::abs(m->pressure - s.pressure) / p_max,
         std::abs(m->tangential_traction + s.tangential_traction) / p_max});
    }
  const double flank_mirror =
    std::max(std::abs(flank_force[0][0] + flank_force[1][0]),
             std::abs(flank_force[0][1] - flank_force[1][1])) /
    centrifugal.norm();

  out << states.size() << " slave nodes, largest pressure "
      << std::setprecision(4) << p_max << " MPa" << std::endl;
  for (unsigned int side : {0, 1})
    out << (side == 0 ? "left " : "right") << " flank: " << n_stick[side]
        << " stick, " << n_slip[side] << " slip, " << n_open[side]
        << " open; force on the blade (" << std::setprecision(6)
        << flank_force[side][0] << ", " << flank_force[side][1]
        << ") N/mm; slip nodes below every stick node: "
        << (highest_slip[side] < lowest_stick[side] ? "yes" : "no")
        << std::endl;
  out << "mirror nodes: same state, pressures equal and tangential tractions "
         "opposite to 1e-11 p_max: "
      << (mirror < 1e-11 ? "yes" : "no")
      << "; flank forces mirror images to 1e-11: "
      << (flank_mirror < 1e-11 ? "yes" : "no") << std::endl
      << "Coulomb cone |lambda_t| <= mu p to 1e-12 p_max at every node: "
      << (cone < 1e-12 ? "yes" : "no")
      << "; slip nodes on the cone to 1e-12 p_max: "
      << (slip_on_cone < 1e-12 ? "yes" : "no") << std::endl;

  AssertThrow(mirror < 1e-11 && flank_mirror < 1e-11,
              ExcMessage("not symmetric: nodes " + std::to_string(mirror) +
                         ", flank forces " + std::to_string(flank_mirror)));
  AssertThrow(cone < 1e-12 && slip_on_cone < 1e-12,
              ExcMessage("outside the Coulomb cone: " + std::to_string(cone) +
                         ", slip nodes off it by " +
                         std::to_string(slip_on_cone)));
  for (unsigned int side : {0, 1})
    AssertThrow(n_stick[side] > 0 && n_slip[side] > 0,
                ExcMessage("no partial slip on a flank"));
}
