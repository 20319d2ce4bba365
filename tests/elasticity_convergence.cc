// Convergence of the elasticity solver on the manufactured solution of the
// 'manufactured' scene (two bodies with different materials), for Q1, Q2
// (quadrilaterals) and P1, P2 (triangles), plane strain, and Q2 in plane
// stress: under uniform refinement the
// energy-norm error must converge at rate p and the L2 error at rate p+1.

#include <deal.II/base/convergence_table.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/elasticity_errors.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

using namespace coulomb_adapt;

void
check(const std::string &cell_type,
      const unsigned int degree,
      const std::string &plane_model = "plane strain")
{
  ParameterHandler prm;
  const Parameters parameters =
    testing::make_parameters(prm,
                             {{"Scene/Name", "manufactured"},
                              {"Mesh/Cell type", cell_type},
                              {"Finite elements/Polynomial degree",
                               std::to_string(degree)},
                              {"Finite elements/Plane model", plane_model}});
  const auto scene = scenes::create_scene(parameters, prm);
  auto       out   = testing::root_output();

  for (unsigned int b = 0; b < 2; ++b)
    {
      ElasticBody         body(MPI_COMM_WORLD,
                       *scene,
                       b,
                       parameters.mesh.cell_type,
                       0,
                       parameters.finite_elements);
      ConvergenceTable    table;
      std::vector<double> l2, energy;
      const unsigned int  n_cycles = (degree == 1) ? 5 : 4;
      for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
        {
          if (cycle > 0)
            body.refine_uniformly();
          body.setup_system();
          body.assemble_system();
          body.solve(parameters.linear_solver);
          const ElasticityErrors e =
            compute_elasticity_errors(body,
                                      *body.description().exact_displacement);
          table.add_value("cells",
                          body.triangulation().n_global_active_cells());
          table.add_value("dofs", body.dof_handler().n_dofs());
          l2.push_back(e.l2);
          energy.push_back(e.energy);
          table.add_value("L2", e.l2);
          table.add_value("energy", e.energy);
        }
      table.set_scientific("L2", true);
      table.set_scientific("energy", true);
      table.set_precision("L2", 3);
      table.set_precision("energy", 3);
      // h halves from one row to the next.
      table.evaluate_convergence_rates("L2",
                                       ConvergenceTable::reduction_rate_log2);
      table.evaluate_convergence_rates("energy",
                                       ConvergenceTable::reduction_rate_log2);

      out << (cell_type == "triangle" ? "P" : "Q") << degree << ", "
          << plane_model << ", body " << b + 1 << " (" << body.name() << ")"
          << std::endl;
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        table.write_text(std::cout);
      out << std::endl;

      // The asymptotic rates, from the last two meshes.
      const auto rate = [](const std::vector<double> &e) {
        return std::log2(e[e.size() - 2] / e.back());
      };
      AssertThrow(std::abs(rate(energy) - degree) < 0.1,
                  ExcMessage("energy-norm rate " +
                             std::to_string(rate(energy)) + " != p"));
      AssertThrow(std::abs(rate(l2) - (degree + 1)) < 0.15,
                  ExcMessage("L2 rate " + std::to_string(rate(l2)) +
                             " != p + 1"));
    }
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const std::string cell_type : {"quadrilateral", "triangle"})
    for (const unsigned int degree : {1u, 2u})
      check(cell_type, degree);
  // Plane stress changes the effective Lame parameter (and the body force).
  check("quadrilateral", 2, "plane stress");
}
