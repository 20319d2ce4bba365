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
      Parameters       parameters = testing::make_parameters(
        prm,
        {{"Scene/Name", "manufactured"},
         {"Mesh/Cell type", cell_type},
         {"Linear solver/Relative tolerance", "1e-12"}});
      const auto scene = scenes::create_scene(parameters, prm);

      for (unsigned int b = 0; b < 2; ++b)
        {
          ElasticBody body(MPI_COMM_WORLD, *scene, b, parameters.mesh.cell_type,
                           2, parameters.finite_elements);
          for (unsigned int cycle = 0; cycle < 3; ++cycle)
            {
              if (cycle > 0)
                body.refine_uniformly();
              body.setup_system();
              body.assemble_system();

              std::map<std::string, TrilinosWrappers::MPI::Vector> solutions;
              unsigned int amg_iterations = 0;
              for (const std::string solver : {"Amesos_Mumps", "Amesos_Klu", "amg"})
                {
                  parameters.linear_solver.type =
                    solver == "amg" ? "amg" : "direct";
                  parameters.linear_solver.direct_solver = solver;
                  const auto report = body.solve(parameters.linear_solver);
                  if (solver == "amg")
                    amg_iterations = report.n_iterations;
                  solutions[solver] = body.solution();
                }
              const double reference = solutions["Amesos_Mumps"].l2_norm();
              double       difference_klu = 0, difference_amg = 0;
              {
                TrilinosWrappers::MPI::Vector d(body.system_rhs());
                d = solutions["Amesos_Klu"];
                TrilinosWrappers::MPI::Vector m(body.system_rhs());
                m = solutions["Amesos_Mumps"];
                d -= m;
                difference_klu = d.l2_norm() / reference;
                d = solutions["amg"];
                d -= m;
                difference_amg = d.l2_norm() / reference;
              }
              out << cell_type << ", body " << b + 1 << ", "
                  << body.dof_handler().n_dofs() << " DoFs: KLU = MUMPS to 1e-12: "
                  << (difference_klu < 1e-12 ? "yes" : "no")
                  << ", AMG = MUMPS to 1e-9: "
                  << (difference_amg < 1e-9 ? "yes" : "no")
                  << ", AMG iterations <= 40: "
                  << (amg_iterations <= 40 ? "yes" : "no") << std::endl;
              AssertThrow(difference_klu < 1e-12 && difference_amg < 1e-9 &&
                            amg_iterations <= 40,
                          ExcMessage("solvers disagree: KLU " +
                                     std::to_string(difference_klu) + ", AMG " +
                                     std::to_string(difference_amg) + " after " +
                                     std::to_string(amg_iterations) +
                                     " iterations"));
            }
        }
    }
}
