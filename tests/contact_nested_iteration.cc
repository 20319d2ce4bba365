// Nested iteration for the first contact solve (contact/nested_iteration.h):
// the sets predicted on coarser meshes of the same scene must
//  - lead to the same solution as the cold start from the initial gap
//    (same node-wise sets; pressure and tangential traction to 1e-8 of the
//    largest pressure; displacements to 1e-8 relative), since the fine
//    Newton iteration runs to its own convergence;
//  - need fewer Newton steps on the fine mesh, at most 4 (the hertz cold
//    start needs 9 here: its first step activates about twice the zone);
// for hertz (graded quadrilaterals, mu = 0.3 and the frictionless path) and
// blocks (triangles, rebuilt from the coarse mesh, mu = 0.3); and, without
// global refinements, on hertz's coarser gradings (its contact zone meshed
// 2, 4, 8 times coarser: gmsh triangles, locally refined quadrilaterals).
// Cold, the graded triangles take 10 Newton steps here. Global
// refinements of a graded scene go down to the scene's own meshes and on
// to their coarser gradings (hertz P1 with one refinement: 9 cold).
// Along a load path every load step starts from the same step on the
// coarser meshes, and ends with the solution of the path without them.
// The program's log says what the coarser meshes did, or why they were
// skipped. A load path (cattaneo: the Hertz contact, then a tangential load
// in 5 steps) predicts its first load step's sets the same way, and its
// later cycles start from the first load step's sets of the cycle before:
// the first step then takes at most 4 Newton steps (cold: 7), every cycle
// reaches the cold start's estimate; the first cycle's later load steps
// take at most 4 (from the coarser meshes' path), no later cycle's
// changes.
// Run on 1 and 2 ranks with the same output.

#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/contact/nested_iteration.h>

#include "contact_test_utilities.h"
#include "program_run.h"

#include <algorithm>

using namespace coulomb_adapt;

namespace
{
  void
  compare(const std::string                                      &name,
          const std::vector<std::pair<std::string, std::string>> &settings,
          const unsigned int                                      n_levels,
          ConditionalOStream                                     &out,
          const bool                                              graded = false,
          const std::string &parameter_file                             = "")
  {
    const auto cold = testing::solve_contact(settings, parameter_file);

    // The same problem again, its sets predicted on n_levels coarser meshes.
    auto nested = testing::solve_contact_setup(settings, parameter_file);
    const auto &p      = nested->parameters;
    std::vector<NestedIterationLevel> levels;
    nested->solver->warm_start_from(
      graded ? predict_contact_sets_on_coarser_graded_meshes(MPI_COMM_WORLD,
                                                             *nested->scene,
                                                             p.mesh.cell_type,
                                                             n_levels,
                                                             p.finite_elements,
                                                             p.contact,
                                                             p.linear_solver,
                                                             levels) :
               predict_contact_sets_on_coarser_meshes(MPI_COMM_WORLD,
                                                      *nested->scene,
                                                      p.mesh.cell_type,
                                                      p.mesh.global_refinements,
                                                      n_levels,
                                                      p.finite_elements,
                                                      p.contact,
                                                      p.linear_solver,
                                                      levels));
    nested->report = nested->solver->solve();

    // Global refinements down to the scene's own graded meshes continue
    // on its coarser gradings: more levels than asked for. A coarser
    // meshing that stops is left out (dovetail's 8x).
    AssertThrow(graded ? !levels.empty() : levels.size() >= n_levels,
                ExcInternalError());
    testing::assert_same_contact_solution(name, *cold, *nested);
    const auto        &a        = cold->solver->node_states();
    const unsigned int n_cold   = cold->report.newton_iterations;
    const unsigned int n_nested = nested->report.newton_iterations;
    AssertThrow(n_nested < n_cold && n_nested <= 4,
                ExcMessage(name + ": Newton steps cold " +
                           std::to_string(n_cold) + ", nested " +
                           std::to_string(n_nested)));
    // Every solve counts, the coarser meshes' too.
    for (const auto &l : levels)
      AssertThrow(l.newton_iterations >= 1 && l.newton_iterations <= 4,
                  ExcMessage(name + ": " + std::to_string(l.n_dofs) +
                             " DoFs coarser mesh: " +
                             std::to_string(l.newton_iterations) +
                             " Newton steps"));

    out << name << ": " << a.size() << " slave nodes, " << cold->report.n_active
        << " active; Newton steps on the fine mesh: " << n_cold
        << " from the initial gap, " << n_nested
        << " after nested iteration (coarser meshes:";
    for (const auto &l : levels)
      out << " " << l.n_dofs << " DoFs " << l.newton_iterations << " steps;";
    out << " same sets: yes, tractions within 1e-8, displacements within "
           "1e-8)"
        << std::endl;
  }

  // Nested iteration along a load path (predict_load_path_on_coarser_meshes):
  // every load step of the fine mesh starts from the same load step's sets
  // on the finest coarser mesh, and must end with the solution of the path
  // without it (from the step before's sets, with the load-step
  // predictor): same node-wise sets, tractions within 1e-8 of the largest
  // pressure, displacements within 1e-8 relative, in every load step; and
  // at most 4 Newton steps in each.
  void
  compare_nested_load_path(
    const std::string                                      &name,
    const std::vector<std::pair<std::string, std::string>> &settings,
    ConditionalOStream                                     &out)
  {
    auto        previous = testing::solve_contact_setup(settings);
    auto        nested   = testing::solve_contact_setup(settings);
    const auto &p        = nested->parameters;
    std::vector<NestedIterationLevel>                levels;
    const std::vector<std::vector<ContactNodeState>> path =
      predict_load_path_on_coarser_meshes(MPI_COMM_WORLD,
                                          *nested->scene,
                                          p.mesh.cell_type,
                                          p.mesh.global_refinements,
                                          p.contact.nested_iteration_levels,
                                          p.mesh.global_refinements == 0,
                                          p.finite_elements,
                                          p.contact,
                                          p.linear_solver,
                                          levels);
    const unsigned int n_steps = nested->scene->n_load_steps();
    AssertThrow(n_steps == 6 && path.size() == n_steps && !levels.empty(),
                ExcInternalError());
    std::ostringstream steps;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        for (auto *q : {previous.get(), nested.get()})
          {
            q->scene->set_load_step(step);
            for (auto &body : q->bodies)
              {
                body->setup_system();
                body->assemble_system();
              }
          }
        const double ratio = previous->scene->load_increment_ratio(step);
        if (ratio > 0)
          previous->solver->predict_next_load_step(ratio);
        nested->solver->warm_start_from(path[step - 1]);
        previous->report = previous->solver->solve();
        nested->report   = nested->solver->solve();

        const std::string where = name + ", load step " + std::to_string(step);
        testing::assert_same_contact_solution(where, *previous, *nested);
        const unsigned int n_previous = previous->report.newton_iterations;
        const unsigned int n          = nested->report.newton_iterations;
        AssertThrow(n <= 4 &&
                      nested->report.newton_iterations_of_stopped_prediction ==
                        0,
                    ExcMessage(where + ": Newton steps from the step before " +
                               std::to_string(n_previous) + ", nested " +
                               std::to_string(n)));
        steps << " " << n_previous << "/" << n;
      }
    for (const auto &l : levels)
      for (const unsigned int k : l.newton_iterations_per_load_step)
        AssertThrow(k <= 4,
                    ExcMessage(name + ": " + std::to_string(l.n_dofs) +
                               " DoFs coarser mesh: a load step took " +
                               std::to_string(k) + " Newton steps"));
    out << name << ": Newton steps per load step from the step before / "
        << "nested:" << steps.str() << " (coarser meshes:";
    for (const auto &l : levels)
      {
        out << " " << l.n_dofs << " DoFs";
        for (const unsigned int k : l.newton_iterations_per_load_step)
          out << " " << k;
        out << ";";
      }
    out << " same sets, tractions within 1e-8, displacements within 1e-8 "
           "in every load step)"
        << std::endl;
  }

  // The program: nested iteration on the first cycle, or the reason why not.
  void
  check_log(const std::vector<std::pair<std::string, std::string>> &settings,
            const std::string                                      &expected,
            ConditionalOStream                                     &out)
  {
    ParameterHandler prm;
    const Parameters parameters = testing::make_parameters(prm, settings);
    prepare_output_directory(parameters.output.directory, MPI_COMM_WORLD);
    std::ostringstream log;
    TwoBodyProblem     problem(MPI_COMM_WORLD, parameters, prm, "test", log);
    problem.run();
    const bool found = log.str().find(expected) != std::string::npos;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      AssertThrow(found,
                  ExcMessage("log lacks '" + expected + "':\n" + log.str()));
    out << "log: '" << expected << "' found" << std::endl;
  }

  // A load path run twice, with and without the predicted starts of the
  // first load step (nested iteration on the first meshes, the previous
  // cycle's first-step sets after): the same estimate in every cycle, the
  // same Newton steps after the first load step, at most 4 in the first.
  void
  compare_load_path(const std::string  &cell_type,
                    const unsigned int  n_cycles,
                    ConditionalOStream &out)
  {
    const std::string cycles = std::to_string(n_cycles);
    const auto        run    = [&](const bool predicted) {
      const testing::ProgramRun run(
        {{"Scene/Name", "cattaneo"},
         {"Mesh/Cell type", cell_type},
         {"Adaptation/Number of cycles", cycles},
         {"Adaptation/Minimum number of cycles", cycles},
         {"Adaptation/Warm start", predicted ? "true" : "false"},
         {"Contact/Nested iteration levels", predicted ? "3" : "0"},
         {"Output/Write VTU", "false"},
         {"Output/Output directory",
          "/tmp/coulomb-adapt-test-nested-path-" + cell_type +
            (predicted ? "-predicted" : "-cold")}});
      return run.summary["cycles"];
    };
    const nlohmann::json cold = run(false), predicted = run(true);
    AssertThrow(cold.size() == n_cycles && predicted.size() == n_cycles,
                ExcInternalError());
    for (unsigned int c = 0; c < n_cycles; ++c)
      {
        const auto                     &a = cold[c], &b = predicted[c];
        const std::vector<unsigned int> steps_cold =
          a["newton_iterations_per_load_step"];
        const std::vector<unsigned int> steps =
          b["newton_iterations_per_load_step"];
        const double e_cold = a["epsilon"], e = b["epsilon"];
        AssertThrow(std::abs(e - e_cold) <= 1e-8 * e_cold,
                    ExcMessage("cattaneo " + cell_type + ", cycle " +
                               std::to_string(c) +
                               ": the predicted start's estimate differs"));
        // The first cycle's later load steps start from the coarser
        // meshes' path (at most 4 steps each); later cycles' as cold.
        AssertThrow(steps.size() == 6 && steps_cold.size() == 6 &&
                      steps[0] <= 4 && steps[0] < steps_cold[0] &&
                      (c == 0 ?
                         *std::max_element(steps.begin(), steps.end()) <= 4 :
                         std::equal(steps.begin() + 1,
                                    steps.end(),
                                    steps_cold.begin() + 1)),
                    ExcMessage("cattaneo " + cell_type + ", cycle " +
                               std::to_string(c) +
                               ": unexpected Newton steps per load step"));
        out << "cattaneo " << cell_type << ", cycle " << c << ", "
            << b["n_dofs"] << " DoFs, "
            << (c == 0 ? "nested iteration" : "previous first-step sets")
            << ": first load step " << steps[0] << " Newton steps (cold "
            << steps_cold[0] << "), later steps";
        for (unsigned int k = 1; k < steps.size(); ++k)
          out << " " << steps[k];
        if (c == 0)
          {
            out << " (cold";
            for (unsigned int k = 1; k < steps_cold.size(); ++k)
              out << " " << steps_cold[k];
            out << ")";
          }
        else
          out << " as cold";
        out << "; epsilon " << std::setprecision(6) << 100 * e << " % as cold"
            << std::endl;
      }
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  compare("hertz Q1, mu = 0.3",
          {{"Scene/Name", "hertz"}, {"Mesh/Global refinements", "1"}},
          1,
          out);
  compare("hertz Q1, mu = 0",
          {{"Scene/Name", "hertz"},
           {"Contact/Friction coefficient", "0"},
           {"Scene/Hertz/Hold axis", "true"},
           {"Mesh/Global refinements", "1"}},
          1,
          out);
  compare("blocks P1, mu = 0.3",
          {{"Scene/Name", "blocks"},
           {"Mesh/Cell type", "triangle"},
           {"Mesh/Global refinements", "3"}},
          2,
          out);

  compare("hertz P1 graded, mu = 0.3",
          {{"Scene/Name", "hertz"},
           {"Mesh/Cell type", "triangle"},
           {"Scene/Hertz/Contact mesh size", "0.025"}},
          3,
          out,
          true);
  compare("hertz Q1 graded, mu = 0",
          {{"Scene/Name", "hertz"},
           {"Contact/Friction coefficient", "0"},
           {"Scene/Hertz/Hold axis", "true"},
           {"Scene/Hertz/Contact mesh size", "0.05"}},
          2,
          out,
          true);

  // A .geo scene meshed at 2, 4 and 8 times its mesh size: dovetail's
  // 8x mesh stops ("would slide") and is left out, the 4x mesh has one
  // active node per flank, and the 2x mesh starts from its closed set.
  compare("dovetail P1 (.geo), mu = 0.5",
          {{"Scene/Gmsh/Mesh file", testing::example_file("meshes/dovetail.geo")}},
          3,
          out,
          true,
          testing::example_file("dovetail.prm"));

  // hertz P1 with one global refinement (15,742 DoFs): its scene's own
  // meshes start from their coarser gradings (cold, 9 Newton steps at
  // this size, 7 on the scene's own meshes).
  compare("hertz P1, 1 global refinement, mu = 0.3",
          {{"Scene/Name", "hertz"},
           {"Mesh/Cell type", "triangle"},
           {"Mesh/Global refinements", "1"}},
          1,
          out);
  compare_nested_load_path("cattaneo P1, 1 global refinement",
                           {{"Scene/Name", "cattaneo"},
                            {"Mesh/Cell type", "triangle"},
                            {"Mesh/Global refinements", "1"}},
                           out);

  compare_load_path("triangle", 2, out);
  compare_load_path("quadrilateral", 1, out);

  const std::string output_directory = "/tmp/coulomb-adapt-test-nested";
  check_log({{"Scene/Name", "blocks"},
             {"Mesh/Global refinements", "2"},
             {"Adaptation/Number of cycles", "1"},
             {"Contact/Nested iteration minimum DoFs", "0"},
             {"Output/Write VTU", "false"},
             {"Output/Output directory", output_directory}},
            "nested iteration, 1 global refinements",
            out);
  check_log({{"Scene/Name", "blocks"},
             {"Mesh/Global refinements", "1"},
             {"Adaptation/Number of cycles", "1"},
             {"Contact/Nested iteration minimum DoFs", "20000"},
             {"Output/Write VTU", "false"},
             {"Output/Output directory", output_directory}},
            "nested iteration skipped: 740 DoFs <= 'Contact/Nested "
            "iteration minimum DoFs' (20000)",
            out);
  check_log({{"Scene/Name", "hertz"},
             {"Scene/Hertz/Contact mesh size", "0.05"},
             {"Adaptation/Number of cycles", "1"},
             {"Output/Write VTU", "false"},
             {"Output/Output directory", output_directory}},
            "nested iteration, graded zone 2x coarser",
            out);
  // Graded meshes below the DoF threshold too (the default hertz, 4,026
  // DoFs on triangles): the threshold is for global refinements only.
  check_log({{"Scene/Name", "hertz"},
             {"Mesh/Cell type", "triangle"},
             {"Adaptation/Number of cycles", "1"},
             {"Output/Write VTU", "false"},
             {"Output/Output directory", output_directory}},
            "nested iteration, graded zone 8x coarser: 830 DoFs",
            out);
}
