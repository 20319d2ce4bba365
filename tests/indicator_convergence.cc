// The error indicator against the exact error:
//  - manufactured elasticity without contact (exact solution known):
//    effectivity epsilon / epsilon_exact within 0.9-1.1 after a few uniform
//    refinements, Q1 and P1, ZZ (L2 projection) and SPR;
//  - hertz (frictionless) against a reference solution two uniform
//    refinements finer: effectivity within 0.7-1.4 on a sequence of meshes;
//  - blocks (the seed's example, P1): epsilon decreases under uniform
//    refinement; the observed rate in the number of DoFs is reported.

#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/indicator/exact_error.h>

#include "contact_test_utilities.h"

#include <cmath>
#include <iomanip>

using namespace coulomb_adapt;

namespace
{
  const std::vector<StressRecoveryMethod> methods =
    {StressRecoveryMethod::l2_projection, StressRecoveryMethod::spr};

  std::array<const ElasticBody *, 2>
  pointers(const std::array<std::unique_ptr<ElasticBody>, 2> &bodies)
  {
    return {{bodies[0].get(), bodies[1].get()}};
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::fixed << std::setprecision(3);

  out << "Manufactured solution, effectivity after uniform refinement"
      << std::endl;
  for (const std::string cell_type : {"quadrilateral", "triangle"})
    for (const auto method : methods)
      for (const std::string refinements : {"3", "4"})
        {
          ParameterHandler prm;
          const Parameters parameters =
            testing::make_parameters(prm,
                                     {{"Scene/Name", "manufactured"},
                                      {"Mesh/Cell type", cell_type},
                                      {"Mesh/Global refinements",
                                       refinements}});
          const auto scene = scenes::create_scene(parameters, prm);
          std::array<std::unique_ptr<ElasticBody>, 2> bodies;
          for (unsigned int b = 0; b < 2; ++b)
            {
              bodies[b] = std::make_unique<ElasticBody>(
                MPI_COMM_WORLD,
                *scene,
                b,
                parameters.mesh.cell_type,
                parameters.mesh.global_refinements,
                parameters.finite_elements);
              bodies[b]->setup_system();
              bodies[b]->assemble_system();
              bodies[b]->solve(parameters.linear_solver);
            }
          const ErrorEstimate e = estimate_error(
            pointers(bodies), nullptr, 0., method, parameters.linear_solver);
          const ExactErrorComparison c =
            compare_with_exact_error(pointers(bodies),
                                     e,
                                     ExactSolutionStress(pointers(bodies)));
          out << "  " << cell_type << ", " << to_string(method)
              << ", refinements " << refinements << ": epsilon "
              << 100 * e.epsilon << " %, exact " << 100 * c.epsilon_exact
              << " %, effectivity " << c.effectivity << std::endl;
          AssertThrow(c.effectivity > 0.9 && c.effectivity < 1.1,
                      ExcMessage("manufactured: effectivity outside 0.9-1.1"));
        }

  out << "Hertz (mu = 0) against a reference solution 2 refinements finer"
      << std::endl;
  for (const std::string refinements : {"0", "1"})
    for (const auto method : methods)
      {
        const std::vector<std::pair<std::string, std::string>> settings = {
          {"Scene/Name", "hertz"},
          {"Scene/Hertz/Contact mesh size", "0.3"},
          {"Mesh/Global refinements", refinements},
          {"Contact/Friction coefficient", "0"}};
        const auto                    p = testing::solve_contact(settings);
        const ErrorEstimate           e = estimate_error(pointers(p->bodies),
                                               p->solver.get(),
                                               0.,
                                               method,
                                               p->parameters.linear_solver);
        const ReferenceSolutionStress reference(
          *p->scene, p->parameters, pointers(p->bodies), 2, false);
        const ExactErrorComparison c =
          compare_with_exact_error(pointers(p->bodies), e, reference);
        const auto n_dofs = p->bodies[0]->dof_handler().n_dofs() +
                            p->bodies[1]->dof_handler().n_dofs();
        out << "  " << n_dofs << " DoFs, " << to_string(method) << ": epsilon "
            << 100 * e.epsilon << " %, reference " << 100 * c.epsilon_exact
            << " %, effectivity " << c.effectivity << std::endl;
        AssertThrow(c.effectivity > 0.7 && c.effectivity < 1.4,
                    ExcMessage("hertz: effectivity outside 0.7-1.4"));
      }

  out << "Blocks (P1, mu = 0.3) under uniform refinement" << std::endl;
  double previous_epsilon = 0, previous_dofs = 0;
  for (const std::string refinements : {"0", "1", "2", "3"})
    {
      const auto p =
        testing::solve_contact({{"Scene/Name", "blocks"},
                                {"Mesh/Cell type", "triangle"},
                                {"Mesh/Global refinements", refinements},
                                {"Contact/Friction coefficient", "0.3"}});
      const ErrorEstimate e =
        estimate_error(pointers(p->bodies),
                       p->solver.get(),
                       0.3,
                       StressRecoveryMethod::l2_projection,
                       p->parameters.linear_solver);
      const auto n_dofs = p->bodies[0]->dof_handler().n_dofs() +
                          p->bodies[1]->dof_handler().n_dofs();
      out << "  " << std::setw(6) << n_dofs << " DoFs: epsilon "
          << 100 * e.epsilon << " %";
      if (previous_dofs > 0)
        {
          out << ", rate in N " << std::setprecision(2)
              << -std::log(e.epsilon / previous_epsilon) /
                   std::log(double(n_dofs) / previous_dofs)
              << std::setprecision(3);
          AssertThrow(e.epsilon < previous_epsilon,
                      ExcMessage("blocks: epsilon does not decrease"));
        }
      out << std::endl;
      previous_epsilon = e.epsilon;
      previous_dofs    = n_dofs;
    }
}
