// The gmsh scene's 'Load steps' on prm/blocks_gmsh.prm (the seed's blocks,
// 4 x 4 and 8 x 8 quadrilaterals, mu = 0.3): step k of n applies k/n of
// every load and prescribed value. Checked against what the load path
// must give without the finite elements:
//  1. the traction (0, -10) MPa on the upper block's top in 4 steps: the
//     contact force on body 1 (held only by contact) balances k/4 of the
//     load 1000 N/mm at step k (to 1e-10 of the load);
//  2. a prescribed displacement 'loaded top: y=-0.01' in 4 steps: the top
//     moves by -0.01 k/4 mm at step k (to 1e-15).

#include <deal.II/numerics/vector_tools.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  // Solve the scene's load path; @p after_step(k, report) after each step.
  template <typename AfterStep>
  void
  solve_load_path(testing::SolvedContactProblem &p, const AfterStep &after_step)
  {
    for (unsigned int step = 1; step <= p.scene->n_load_steps(); ++step)
      {
        p.scene->set_load_step(step);
        for (auto &body : p.bodies)
          {
            body->setup_system();
            body->assemble_system();
          }
        after_step(step, p.solver->solve());
      }
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  const std::string prm = testing::example_file("blocks_gmsh.prm");
  const std::string geo = testing::example_file("meshes/blocks_structured.geo");
  const unsigned int n_steps = 4;

  out << "1. traction (0, -10) MPa on the top in " << n_steps << " load steps"
      << std::endl;
  {
    auto p = testing::solve_contact_setup({{"Scene/Gmsh/Mesh file", geo},
                                           {"Scene/Gmsh/Load steps",
                                            std::to_string(n_steps)}},
                                          prm);
    AssertThrow(p->scene->n_load_steps() == n_steps,
                ExcMessage("the scene's load steps are not 'Load steps'"));
    solve_load_path(*p, [&](const unsigned int step, const auto &report) {
      const double expected = 1000. * step / n_steps;
      const double error =
        (report.contact_force - Tensor<1, 2>({0., expected})).norm() / 1000.;
      out << "  step " << step << ": contact force on body 1 y "
          << std::setprecision(6) << report.contact_force[1]
          << " N/mm, expected (0, " << expected
          << ") (within 1e-10 of the load): " << (error < 1e-10 ? "yes" : "no")
          << std::endl;
      AssertThrow(error < 1e-10,
                  ExcMessage("contact force off by " + std::to_string(error)));
    });
  }

  out << "2. prescribed displacement y = -0.01 mm on the top in " << n_steps
      << " load steps" << std::endl;
  {
    auto p = testing::solve_contact_setup(
      {{"Scene/Gmsh/Mesh file", geo},
       {"Scene/Gmsh/Tractions", ""},
       {"Scene/Gmsh/Fixed components", "base: x y, loaded top: y=-0.01"},
       {"Scene/Gmsh/Load steps", std::to_string(n_steps)}},
      prm);
    solve_load_path(*p, [&](const unsigned int step, const auto &) {
      Vector<double> u(2);
      VectorTools::point_value(p->bodies[0]->mapping(),
                               p->bodies[0]->dof_handler(),
                               p->bodies[0]->solution(),
                               Point<2>(100, 300),
                               u);
      const double expected = -0.01 * step / n_steps;
      out << "  step " << step << ": u_y(100, 300) = " << std::setprecision(10)
          << u[1] << " mm, expected " << expected << " (within 1e-15): "
          << (std::abs(u[1] - expected) <= 1e-15 ? "yes" : "no") << std::endl;
      AssertThrow(std::abs(u[1] - expected) <= 1e-15,
                  ExcMessage("the top is not at k/n of its displacement"));
    });
  }
}
