// The gmsh scene's loads per group and per body, on prm/blocks_gmsh.prm
// (the seed's blocks, 4 x 4 and 8 x 8 quadrilaterals, mu = 0.3), each
// against a number known without the finite elements:
//  1. 'Normal pressures = loaded top: 10' is the traction (0, -10) there:
//     the same contact pressures (to round-off);
//  2. gravity on body 1 only (density 7.85e-9 t/mm^3, g = 9810 mm/s^2):
//     the contact force is the block's weight rho g A, A = 100 x 100 mm^2;
//  3. centrifugal load on body 1 about an axis through (100, 1000)
//     (omega = 100 rad/s): the contact force is rho omega^2 A times the
//     distance 750 mm of the block's centroid from the axis, towards it
//     (down), and has no horizontal part;
//  4. a prescribed displacement 'loaded top: y=-0.01' instead of a load:
//     the top moves by -0.01 mm exactly, and the contact is compressed.
// The contact force balances the applied load to 1e-10 relative.

#include <deal.II/numerics/vector_tools.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  const double                     rho = 7.85e-9, area = 100 * 100;

  const auto solve = [](const testing::Settings &settings) {
    return testing::solve_example("blocks_gmsh.prm",
                                  "blocks_structured.geo",
                                  settings);
  };
  const auto check =
    [&](const std::string &what, const double error, const double tolerance) {
      out << "  " << what << " (within " << tolerance
          << "): " << (error <= tolerance ? "yes" : "no") << std::endl;
      AssertThrow(error <= tolerance,
                  ExcMessage(what + ": " + std::to_string(error)));
    };

  out << "1. normal pressure 10 MPa against the traction (0, -10) MPa"
      << std::endl;
  {
    const auto traction = solve({});
    const auto pressure =
      solve({{"Scene/Gmsh/Tractions", ""},
             {"Scene/Gmsh/Normal pressures", "loaded top: 10"}});
    check("same contact tractions, relative to max pressure",
          testing::relative_traction_difference(
            traction->solver->node_states(), pressure->solver->node_states()),
          1e-12);
  }

  const auto force_check = [&](const std::string                   &name,
                               const testing::SolvedContactProblem &p,
                               const Tensor<1, 2>                  &expected) {
    out << "  contact force on body 1 (" << std::setprecision(8)
        << (std::abs(p.report.contact_force[0]) < 1e-9 * expected.norm() ?
              0. :
              p.report.contact_force[0])
        << ", " << p.report.contact_force[1] << ") N/mm, expected ("
        << expected[0] << ", " << expected[1] << ")" << std::endl;
    check(name,
          (p.report.contact_force - expected).norm() / expected.norm(),
          1e-10);
  };

  out << "2. gravity on body 1" << std::endl;
  {
    const auto p = solve({{"Scene/Gmsh/Tractions", ""},
                          {"Scene/Gmsh/Body 1/Density", "7.85e-9"},
                          {"Scene/Gmsh/Body 1/Gravity", "0, -9810"}});
    force_check("weight rho g A", *p, Tensor<1, 2>({0., rho * 9810 * area}));
  }

  out << "3. centrifugal load on body 1, axis at (100, 1000)" << std::endl;
  {
    const auto p = solve({{"Scene/Gmsh/Tractions", ""},
                          {"Scene/Gmsh/Body 1/Density", "7.85e-9"},
                          {"Scene/Gmsh/Body 1/Angular velocity", "100"},
                          {"Scene/Gmsh/Body 1/Rotation axis", "100, 1000"}});
    force_check("rho omega^2 A (centroid - axis)",
                *p,
                Tensor<1, 2>({0., rho * 1e4 * area * 750}));
  }

  out << "4. prescribed displacement y = -0.01 mm on the top" << std::endl;
  {
    const auto p = solve(
      {{"Scene/Gmsh/Tractions", ""},
       {"Scene/Gmsh/Fixed components", "base: x y, loaded top: y=-0.01"}});
    Vector<double> u(2);
    VectorTools::point_value(p->bodies[0]->mapping(),
                             p->bodies[0]->dof_handler(),
                             p->bodies[0]->solution(),
                             Point<2>(100, 300),
                             u);
    out << "  u_y(100, 300) = " << std::setprecision(10) << u[1]
        << " mm; contact force y " << std::setprecision(6)
        << p->report.contact_force[1] << " N/mm" << std::endl;
    check("u_y = -0.01 on the top", std::abs(u[1] + 0.01), 1e-15);
    out << "  compressed contact (force y > 0): "
        << (p->report.contact_force[1] > 0 ? "yes" : "no") << std::endl;
    AssertThrow(p->report.contact_force[1] > 0,
                ExcMessage("the prescribed displacement does not press"));
  }
}
