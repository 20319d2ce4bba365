// The program's restarts of a static contact solve that stops with a
// diagnosis (TwoBodyProblem::solve_contact). With a user-scaled
// complementarity constant the last restart uses the natural constants
// c = E_c/h, because the solution does not depend on c and an extreme
// scale can keep the active set iteration from settling:
//  - stability sweep case 241, coarsened (blocks, triangles, 32x32 on 8x8
//    without refinement, E1/E2 = 1e3, nu = 0.499, mu = 1.5, load x 1e6,
//    c x 1e3): the sets wander for 37 steps with c x 1e3, 10 with c x 1.
//    With at most 20 steps the run must restart with the natural
//    constants, say so in the log and summary.json, and converge;
//  - the result must be the solution of c x 1e3 itself, obtained with
//    100 steps allowed (c-independence, the independent truth here): the
//    same active/stick/slip counts, the largest pressure and the contact
//    force to 1e-8;
//  - a problem without equilibrium (mu = 0, body 1 not held sideways,
//    c x 10) must still stop with its diagnosis after the restart, and the
//    restart must not hide it;
//  - on 1 rank, case 241 itself (one refinement, nested iteration, 40
//    steps allowed): the nested start and the initial gap reach the limit,
//    the natural constants from the nested sets converge (summary.json
//    records both restarts and the steps of the stopped starts), to the
//    sets of the coarsened case's solution family: 47 active, 11 stick,
//    36 slip, as the same case at load x 1 and c x 1 (sweep case 262).
// 1 and 2 ranks (241 itself on 1 rank only: about 25 s).

#include <coulomb_adapt/app/two_body_problem.h>

#include "contact_test_utilities.h"

#include <nlohmann/json.hpp>

#include <fstream>

using namespace coulomb_adapt;

namespace
{
  using Settings = std::vector<std::pair<std::string, std::string>>;

  const std::string output_directory = "/tmp/coulomb-adapt-test-restart";

  Settings
  with(Settings settings, const Settings &more)
  {
    settings.insert(settings.end(), more.begin(), more.end());
    return settings;
  }

  // The program on @p settings (one cycle, no VTU): its log and the
  // summary of cycle 0. Throws what the program throws.
  nlohmann::json
  run_program(const Settings &settings, std::string &log_text)
  {
    ParameterHandler prm;
    const Parameters parameters = testing::make_parameters(
      prm,
      with(settings,
           {{"Adaptation/Number of cycles", "1"},
            {"Output/Write VTU", "false"},
            {"Output/Output directory", output_directory}}));
    prepare_output_directory(parameters.output.directory, MPI_COMM_WORLD);
    std::ostringstream log;
    TwoBodyProblem     problem(MPI_COMM_WORLD, parameters, prm, "test", log);
    try
      {
        problem.run();
      }
    catch (...)
      {
        log_text = log.str();
        throw;
      }
    log_text = log.str();
    // Rank 0 writes the summary; the others read it once it is complete.
    MPI_Barrier(MPI_COMM_WORLD);
    nlohmann::json summary;
    std::ifstream(output_directory + "/summary.json") >> summary;
    return summary["cycles"][0];
  }

  void
  assert_in_log(const std::string &log, const std::string &expected)
  {
    // Only rank 0 writes the log.
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      AssertThrow(log.find(expected) != std::string::npos,
                  ExcMessage("log lacks '" + expected + "':\n" + log));
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const Settings case_241 =
    with(testing::stiff_slave_blocks("10000000", "32, 32", "8, 8"),
         {{"Mesh/Cell type", "triangle"},
          {"Mesh/Global refinements", "0"},
          {"Contact/Friction coefficient", "1.5"},
          {"Contact/Complementarity scale", "1000"}});

  // The truth: the user's c x 1e3, given the steps it needs.
  const auto scaled = testing::solve_contact(
    with(case_241, {{"Contact/Maximum Newton iterations", "100"}}));
  AssertThrow(scaled->report.converged, ExcInternalError());
  AssertThrow(scaled->report.newton_iterations > 20,
              ExcMessage("c x 1e3 converges within 20 steps (" +
                         std::to_string(scaled->report.newton_iterations) +
                         "): the test no longer needs a restart"));

  std::string          log;
  const nlohmann::json cycle =
    run_program(with(case_241, {{"Contact/Maximum Newton iterations", "20"}}),
                log);
  assert_in_log(log, "did not converge in 20 steps");
  assert_in_log(log,
                "solving again with the natural constants c = E_c/h "
                "('Contact/Complementarity scale' = 1 instead of 1000), "
                "from the initial gap");
  AssertThrow(cycle["converged"].get<bool>(), ExcInternalError());
  AssertThrow(cycle.value("retried_with_natural_complementarity_scale", false),
              ExcMessage("summary.json does not record the restart"));
  AssertThrow(!cycle.contains("retried_from_initial_gap"),
              ExcMessage("a cold start was restarted from the initial gap"));

  const auto &r = scaled->report;
  AssertThrow(cycle["active_nodes"].get<unsigned int>() == r.n_active &&
                cycle["stick_nodes"].get<unsigned int>() == r.n_stick &&
                cycle["slip_nodes"].get<unsigned int>() == r.n_slip,
              ExcMessage("the restart's sets differ from c x 1e3's"));
  const double p_max = r.max_contact_pressure;
  const double p_diff =
    std::abs(cycle["max_contact_pressure"].get<double>() - p_max) / p_max;
  const double load   = std::abs(r.contact_force[1]);
  double       f_diff = 0;
  for (unsigned int d = 0; d < 2; ++d)
    f_diff = std::max(f_diff,
                      std::abs(cycle["contact_force"][d].get<double>() -
                               r.contact_force[d]) /
                        load);
  AssertThrow(p_diff <= 1e-8 && f_diff <= 1e-8,
              ExcMessage("largest pressure differs by " +
                         std::to_string(p_diff) + ", contact force by " +
                         std::to_string(f_diff)));
  out << "case 241 coarsened, c x 1e3: converges in more than 20 steps; "
         "with 20 allowed the run restarts with the natural constants and "
         "converges: "
      << r.n_active << " active, " << r.n_stick << " stick, " << r.n_slip
      << " slip as with c x 1e3; largest pressure and contact force within "
         "1e-8"
      << std::endl;

  // No equilibrium: the restart tries, and the diagnosis stands.
  bool stopped = false;
  try
    {
      run_program({{"Scene/Name", "blocks"},
                   {"Scene/Blocks/Hold centre line", "false"},
                   {"Contact/Friction coefficient", "0"},
                   {"Contact/Complementarity scale", "10"}},
                  log);
    }
  catch (const std::exception &e)
    {
      stopped                = true;
      const std::string what = e.what();
      AssertThrow(what.find("can slide freely") != std::string::npos,
                  ExcMessage("unexpected stop: " + what));
    }
  AssertThrow(stopped, ExcMessage("mu = 0 without hold did not stop"));
  assert_in_log(log, "solving again with the natural constants");
  out << "mu = 0, body 1 not held, c x 10: restarted with the natural "
         "constants, still stops with 'can slide freely'"
      << std::endl;

  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    return 0;
  const nlohmann::json full =
    run_program(with(case_241,
                     {{"Mesh/Global refinements", "1"},
                      {"Contact/Nested iteration minimum DoFs", "0"}}),
                log);
  assert_in_log(log,
                "contact: Newton starts from the sets of the coarser "
                "meshes (nested iteration)");
  assert_in_log(log, "solving again from the initial gap");
  assert_in_log(log,
                "solving again with the natural constants c = E_c/h "
                "('Contact/Complementarity scale' = 1 instead of 1000), "
                "from the predicted sets");
  AssertThrow(
    full["converged"].get<bool>() &&
      full.value("retried_from_initial_gap", false) &&
      full.value("retried_with_natural_complementarity_scale", false) &&
      full["newton_iterations_of_stopped_starts"].get<unsigned int>() == 80,
    ExcMessage("case 241: " + full.dump()));
  AssertThrow(full["active_nodes"].get<unsigned int>() == 47 &&
                full["stick_nodes"].get<unsigned int>() == 11 &&
                full["slip_nodes"].get<unsigned int>() == 36,
              ExcMessage("case 241: other sets: " + full.dump()));
  out << "case 241: the nested start and the initial gap stop at 40 steps, "
         "the natural constants from the nested sets converge in "
      << full["newton_iterations"].get<unsigned int>()
      << " steps: 47 active, 11 stick, 36 slip" << std::endl;
}
