// The linear solvers agree: the manufactured elasticity problem (Q1 and P1,
// both bodies) solved by MUMPS, by KLU and by CG + ML AMG with the rigid
// body modes gives the same displacement (to the CG tolerance), and AMG
// needs few iterations, independently of the mesh size.

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  for (const std::string cell_type : {"quadrilateral", "triangle"})
    {
      ParameterHandler prm;
      Parameters       parameters =
        testing::make_parameters(prm,
                                 {{"Scene/Name", "manufactured"},
                                  {"Mesh/Cell type", cell_type},
                                  {"Linear solver/Relative tolerance",
                                   "1e-12"}});
      const auto scene = scenes::create_scene(parameters, prm);

      for (unsigned int b = 0; b < 2; ++b)
        {
          ElasticBody body(MPI_COMM_WORLD,
                           *scene,
                           b,
                           parameters.mesh.cell_type,
                           2,
                           parameters.finite_elements);
          for (unsigned int cycle = 0; cycle < 3; ++cycle)
            {
              if (cycle > 0)
                body.refine_uniformly();
              body.setup_system();
              body.assemble_system();

              std::map<std::string, TrilinosWrappers::MPI::Vector> solutions;
              unsigned int amg_iterations = 0;
              for (const std::string solver :
                   {"Amesos_Mumps", "Amesos_Klu", "amg"})
                {
                  parameters.linear_solver.type          = solver == "amg" ?
                                                             LinearSolverType::amg :
                                                             LinearSolverType::direct;
                  parameters.linear_solver.direct_solver = solver;
                  const auto report = body.solve(parameters.linear_solver);
                  if (solver == "amg")
                    amg_iterations = report.n_iterations;
                  solutions[solver] = body.solution();
                }
              // Relative l2 differences over the locally owned entries.
              const IndexSet owned = body.dof_handler().locally_owned_dofs();
              const auto relative_difference = [&](const std::string &name) {
                double difference = 0, reference = 0;
                for (const auto i : owned)
                  {
                    const double r = solutions["Amesos_Mumps"][i];
                    difference += std::pow(solutions[name][i] - r, 2);
                    reference += r * r;
                  }
                return std::sqrt(
                  Utilities::MPI::sum(difference, MPI_COMM_WORLD) /
                  Utilities::MPI::sum(reference, MPI_COMM_WORLD));
              };
              const double difference_klu = relative_difference("Amesos_Klu");
              const double difference_amg = relative_difference("amg");
              out << cell_type << ", body " << b + 1 << ", "
                  << body.dof_handler().n_dofs()
                  << " DoFs: KLU = MUMPS to 1e-12: "
                  << (difference_klu < 1e-12 ? "yes" : "no")
                  << ", AMG = MUMPS to 1e-9: "
                  << (difference_amg < 1e-9 ? "yes" : "no")
                  << ", AMG iterations <= 40: "
                  << (amg_iterations <= 40 ? "yes" : "no") << std::endl;
              AssertThrow(difference_klu < 1e-12 && difference_amg < 1e-9 &&
                            amg_iterations <= 40,
                          ExcMessage(
                            "solvers disagree: KLU " +
                            std::to_string(difference_klu) + ", AMG " +
                            std::to_string(difference_amg) + " after " +
                            std::to_string(amg_iterations) + " iterations"));
            }
        }
    }
}
