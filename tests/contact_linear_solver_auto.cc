// 'Linear solver/Type = auto' for the contact Newton systems
// (contact/contact_linear_solver_choice.h): direct up to 'Maximum DoFs for
// direct contact' (DoFs of both bodies), Krylov + AMG on the eliminated
// system above.
//  - The choice on either side of the threshold, for the default threshold
//    and for one set to the problem's size: n_dofs <= threshold is direct,
//    n_dofs = threshold + 1 is AMG; 'direct' and 'amg' are taken as given.
//  - The solver that ran (its report's method) is the one chosen, with
//    friction (GMRES) and without (CG).
//  - Both give the same solution to the solvers' tolerance: same
//    node-wise sets, pressure and tangential traction within 1e-8 of the
//    largest pressure, displacements within 1e-8 relative.
//  - The program's log states the solver and why.
// 1 and 2 ranks (the choice is by the global number of DoFs).

#include <coulomb_adapt/contact/contact_linear_solver_choice.h>

#include "contact_test_utilities.h"
#include "program_run.h"

using namespace coulomb_adapt;

namespace
{
  using Settings = std::vector<std::pair<std::string, std::string>>;

  Settings
  with_threshold(Settings settings, const types::global_dof_index threshold)
  {
    settings.emplace_back("Linear solver/Type", "auto");
    settings.emplace_back("Linear solver/Maximum DoFs for direct contact",
                          std::to_string(threshold));
    return settings;
  }

  types::global_dof_index
  n_dofs(const testing::SolvedContactProblem &p)
  {
    return p.bodies[0]->dof_handler().n_dofs() +
           p.bodies[1]->dof_handler().n_dofs();
  }

  void
  check_choice_rule(ConditionalOStream &out)
  {
    ParameterHandler prm;
    auto p = testing::make_parameters(prm, {}).linear_solver;
    const types::global_dof_index threshold = p.max_dofs_for_direct_contact;
    AssertThrow(p.type == LinearSolverType::automatic, ExcInternalError());
    AssertThrow(!choose_contact_linear_solver(p, threshold).iterative &&
                  choose_contact_linear_solver(p, threshold + 1).iterative,
                ExcMessage("auto: not direct up to the threshold and AMG "
                           "above"));
    out << "default: auto, direct up to " << threshold << " DoFs: "
        << choose_contact_linear_solver(p, threshold).description << "; "
        << choose_contact_linear_solver(p, threshold + 1).description
        << std::endl;
    for (const auto type : {LinearSolverType::direct, LinearSolverType::amg})
      {
        p.type = type;
        for (const types::global_dof_index n : {threshold, threshold + 1})
          AssertThrow(choose_contact_linear_solver(p, n).iterative ==
                        (type == LinearSolverType::amg),
                      ExcMessage("direct / amg not taken as given"));
        out << choose_contact_linear_solver(p, 1).description << std::endl;
      }
  }

  // The problem solved with the threshold at its size (direct) and one
  // below (AMG).
  void
  compare(const std::string  &name,
          const Settings     &settings,
          ConditionalOStream &out)
  {
    const auto                    probe = testing::solve_contact_setup(settings);
    const types::global_dof_index n     = n_dofs(*probe);
    const auto direct = testing::solve_contact(with_threshold(settings, n));
    const auto amg    = testing::solve_contact(with_threshold(settings, n - 1));
    const std::string direct_method =
      direct->solver->last_linear_solver_report().method;
    const std::string amg_method =
      amg->solver->last_linear_solver_report().method;
    AssertThrow(direct_method.find("direct") == 0 &&
                  amg_method.find("+amg") != std::string::npos,
                ExcMessage(name + ": ran " + direct_method + " and " +
                           amg_method));
    testing::assert_same_contact_solution(name, *direct, *amg);
    out << name << ", " << n << " DoFs: threshold " << n << " -> "
        << direct_method << ", threshold " << n - 1 << " -> " << amg_method
        << "; " << amg->report.n_active
        << " active, same sets, tractions and displacements within 1e-8"
        << std::endl;
  }

  void
  check_log(ConditionalOStream &out)
  {
    const testing::ProgramRun run(
      {{"Scene/Name", "blocks"},
       {"Mesh/Cell type", "triangle"},
       {"Mesh/Global refinements", "1"},
       {"Adaptation/Number of cycles", "1"},
       {"Adaptation/Minimum number of cycles", "1"},
       {"Linear solver/Maximum DoFs for direct contact", "1000"},
       {"Output/Write VTU", "false"},
       {"Output/Output directory", "/tmp/coulomb-adapt-test-solver-auto"}});
    const std::string expected =
      "contact: linear solver Krylov + AMG (eliminated system: CG without "
      "friction, GMRES with): 2756 DoFs > 'Linear solver/Maximum DoFs for "
      "direct contact' (1000), 'Linear solver/Type' = auto";
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      AssertThrow(run.log.str().find(expected) != std::string::npos,
                  ExcMessage("log lacks '" + expected + "':\n" +
                             run.log.str()));
    out << "log: '" << expected << "' found" << std::endl;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  check_choice_rule(out);
  compare("blocks P1, mu = 0.3",
          {{"Scene/Name", "blocks"},
           {"Mesh/Cell type", "triangle"},
           {"Mesh/Global refinements", "2"}},
          out);
  compare("hertz Q1, mu = 0",
          {{"Scene/Name", "hertz"},
           {"Contact/Friction coefficient", "0"},
           {"Scene/Hertz/Hold axis", "true"}},
          out);
  check_log(out);
}
