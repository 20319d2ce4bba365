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
//  - The fallback: under 'auto', a Krylov solve that does not converge
//    (here 'Maximum iterations' = 2) hands its Newton system to the direct
//    solver, and the shared KrylovFailureRecord sends every later system
//    there at once: over two load steps on one solver and a second solver
//    sharing the record (the driver's restarts and cycles), exactly one
//    failed Krylov solve, every solve then direct, the same Newton steps
//    and the same solution as the direct solver's (sets, tractions and
//    displacements within 1e-8). The program says so once in its log,
//    states the reason in the next cycle's solver line, and summary.json
//    records the failure.
// 1 and 2 ranks (the choice is by the global number of DoFs).

#include <coulomb_adapt/contact/contact_linear_solver_choice.h>
#include <coulomb_adapt/contact/contact_solver.h>

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

  // GMRES (mu = 0.3) stopped after 2 iterations on blocks P1 (2756 DoFs,
  // threshold 1000).
  void
  check_fallback(ConditionalOStream &out)
  {
    const Settings settings = {{"Scene/Name", "blocks"},
                               {"Mesh/Cell type", "triangle"},
                               {"Mesh/Global refinements", "1"}};
    const auto     direct =
      testing::solve_contact(with_threshold(settings, 100000));
    Settings failing = with_threshold(settings, 1000);
    failing.emplace_back("Linear solver/Maximum iterations", "2");
    auto       p      = testing::solve_contact_setup(failing);
    const auto record = std::make_shared<KrylovFailureRecord>();
    static const ConditionalOStream quiet(std::cout, false);
    const auto new_solver = [&]() {
      return std::make_unique<ContactSolver>(*p->bodies[0],
                                             *p->bodies[1],
                                             p->parameters.contact,
                                             p->parameters.linear_solver,
                                             quiet,
                                             record);
    };
    p->solver = new_solver();
    p->report = p->solver->solve();
    const auto check = [&](const std::string &where) {
      const std::string method = p->solver->last_linear_solver_report().method;
      AssertThrow(record->n_failed_solves == 1 && method.find("direct") == 0,
                  ExcMessage("fallback, " + where + ": " +
                             std::to_string(record->n_failed_solves) +
                             " failed Krylov solves, last solve " + method));
      testing::assert_same_contact_solution("fallback, " + where, *direct, *p);
    };
    AssertThrow(p->report.newton_iterations ==
                  direct->report.newton_iterations,
                ExcMessage("fallback: Newton steps " +
                           std::to_string(p->report.newton_iterations) +
                           ", direct " +
                           std::to_string(direct->report.newton_iterations)));
    check("first solve");
    p->report = p->solver->solve();
    check("second load step");
    p->solver = new_solver();
    p->report = p->solver->solve();
    check("second solver sharing the record");
    out << "fallback, blocks P1, " << n_dofs(*p)
        << " DoFs, threshold 1000, 2 Krylov iterations allowed: 1 failed "
           "Krylov solve in 3 solves, then direct; "
        << direct->report.newton_iterations
        << " Newton steps as direct; same sets, tractions and "
           "displacements within 1e-8"
        << std::endl;

    // The program: 2 cycles, the first one's Krylov solve fails.
    const testing::ProgramRun run(
      {{"Scene/Name", "blocks"},
       {"Mesh/Cell type", "triangle"},
       {"Mesh/Global refinements", "1"},
       {"Adaptation/Number of cycles", "2"},
       {"Adaptation/Minimum number of cycles", "2"},
       {"Linear solver/Maximum DoFs for direct contact", "1000"},
       {"Linear solver/Maximum iterations", "2"},
       {"Output/Write VTU", "false"},
       {"Output/Output directory", "/tmp/coulomb-adapt-test-solver-fallback"}});
    const std::string log         = run.log.str();
    const std::string failed      = "the Krylov solve did not converge in 2 "
                                    "iterations";
    const std::string later       = "but Krylov + AMG did not converge on an "
                                    "earlier Newton system (Newton step 1, "
                                    "2756 DoFs: stopped at 2 iterations";
    const auto        first       = log.find(failed);
    const bool        logged_once = first != std::string::npos &&
                             log.find(failed, first + 1) == std::string::npos;
    const auto &cycles = run.summary["cycles"];
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      AssertThrow(logged_once && log.find(later) != std::string::npos &&
                    cycles.size() == 2 &&
                    cycles[0]["linear_solver"][0].contains("krylov_failure") &&
                    cycles[1]["linear_solver"][0]["method"] ==
                      "direct (Amesos_Mumps)",
                  ExcMessage("fallback: log or summary.json:\n" + log));
    out << "fallback, program, 2 cycles: '" << failed
        << "' once; the second cycle's solver line: '... " << later
        << " ...'; summary.json: krylov_failure" << std::endl;
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
  check_fallback(out);
}
