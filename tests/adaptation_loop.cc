// The adaptation loop of theory.md section 4 on the seed's scene (blocks):
//  - remesh (P1 triangles, gmsh frontal-Delaunay and Delaunay) and refine
//    (Q1, hanging nodes, flags from
//    r_E; and GridRefinement-style 'optimize') reach epsilon <= epsilon_0
//    for epsilon_0 = 5 %, 2 % and (remesh from the seed's mesh) 1 %, and
//    stop for that reason;
//  - the strategies that plan the optimal mesh (remesh, refine with 'size
//    ratio') need at most 2 adaptation steps for it: the plan aims below
//    epsilon_0 by the safety factor and the measured/predicted ratio of
//    the previous plan (TargetCalibration);
//  - the first remesh step from the seed's mesh (408 P1 triangles) lands
//    within 25 % of the predicted cell count N* (on meshes of ~200 cells
//    gmsh overshoots N* by ~30 %: too few cells between the boundaries);
//  - the finest cells of the final meshes sit at the ends of the contact
//    zone (x = 50 and x = 150 on y = 200), where the indicator density of
//    the initial mesh is largest;
//  - 'Maximum number of DoFs' bounds the adapted meshes too: for an
//    epsilon_0 far below reach (0.01 %) the size ratios alone let the mesh
//    grow up to 100-fold per cycle (here 68 -> 2,756 -> 165,380 DoFs
//    without a cap; 4.2e5 -> 2.7e7 DoFs, killed for memory, on the seed's
//    mesh with the default cap of 2e6). With a cap of 3000 DoFs every mesh
//    stays within 4 times the cap (one level of refinement: the refine
//    strategy rounds r_E to whole levels, which gave 1.25 times here, 2.2
//    before its threshold aimed at the capped plan's prediction; gmsh
//    1.06 times) and the log says the mesh was limited;
//  - an epsilon_0 far above reach (100 %) with 'Over-refinement ratio'
//    coarsens down to 'Minimum number of cells' (100) and stops there,
//    with at least that many cells (it went on to 4 + 4 triangles, where
//    zz is meaningless); with no minimum, down to gmsh's coarsest mesh of
//    the geometry, and it stops at its first repeat (it used to solve it
//    on every cycle left);
//  - the 2-rank run prints what the 1-rank run prints (same meshes, DoFs,
//    epsilon, Newton steps).

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/two_body_problem.h>

#include "program_run.h"
#include "test_utilities.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>

using namespace coulomb_adapt;

namespace
{
  const std::array<Point<2>, 2> contact_zone_ends = {
    {Point<2>(50, 200), Point<2>(150, 200)}};

  double
  distance_to_contact_zone_ends(const Point<2> &p)
  {
    return std::min(p.distance(contact_zone_ends[0]),
                    p.distance(contact_zone_ends[1]));
  }

  using testing::ProgramRun;
  using testing::Settings;

  Settings
  blocks(const std::string &cell_type,
         const std::string &strategy,
         const std::string &upper,
         const std::string &lower,
         const std::string &target,
         const std::string &directory)
  {
    return {{"Scene/Name", "blocks"},
            {"Scene/Blocks/Upper body subdivisions", upper},
            {"Scene/Blocks/Lower body subdivisions", lower},
            {"Contact/Friction coefficient", "0.3"},
            {"Mesh/Cell type", cell_type},
            {"Adaptation/Strategy", strategy},
            {"Adaptation/Target error", target},
            {"Adaptation/Number of cycles", "12"},
            {"Output/Write VTU", "false"},
            {"Output/Output directory", directory}};
  }

  // The cells of each body whose diameter is within 1 % of the body's
  // smallest: how far from a contact zone end the farthest of them lies.
  void
  check_finest_cells(const TwoBodyProblem &problem,
                     const double          max_distance,
                     ConditionalOStream   &out)
  {
    for (unsigned int b = 0; b < 2; ++b)
      {
        const auto &tria  = problem.body(b).triangulation();
        double      h_min = std::numeric_limits<double>::max();
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            h_min = std::min(h_min, cell->diameter());
        h_min           = Utilities::MPI::min(h_min, MPI_COMM_WORLD);
        double farthest = 0;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned() && cell->diameter() <= 1.01 * h_min)
            farthest =
              std::max(farthest, distance_to_contact_zone_ends(cell->center()));
        farthest = Utilities::MPI::max(farthest, MPI_COMM_WORLD);
        out << "    body " << b + 1 << ": finest cells (diameter " << h_min
            << " mm) at most " << farthest << " mm from a contact zone end"
            << std::endl;
        AssertThrow(farthest <= max_distance,
                    ExcMessage("the finest cells are not at the ends of the "
                               "contact zone"));
      }
  }

  // @p max_adaptation_steps: 0 for no limit (the fixed-fraction and
  // optimize criteria, which do not aim at epsilon_0).
  void
  run_loop(const Settings     &settings,
           const double        target,
           const bool          check_finest,
           const bool          check_prediction,
           const unsigned int  max_adaptation_steps,
           ConditionalOStream &out)
  {
    const ProgramRun      run(settings);
    const nlohmann::json &summary = run.summary;
    const auto           &cycles  = summary["cycles"];
    for (const auto &c : cycles)
      {
        out << "    cycle " << c["cycle"].get<unsigned int>() << ": cells "
            << c["bodies"][0]["n_cells"].get<unsigned int>() << " + "
            << c["bodies"][1]["n_cells"].get<unsigned int>() << ", DoFs "
            << c["n_dofs"].get<unsigned int>() << ", epsilon "
            << 100 * c["epsilon"].get<double>() << " %, Newton "
            << c["newton_iterations"].get<unsigned int>();
        if (c.contains("adaptation") &&
            c["adaptation"].contains("predicted_n_cells"))
          {
            const double predicted =
              c["adaptation"]["predicted_n_cells"].get<double>();
            const double obtained =
              c["adaptation"]["obtained_n_cells"].get<double>();
            out << ", N* " << std::lround(predicted) << " planned for "
                << 100 * c["adaptation"]["aimed_epsilon"].get<double>() << " %";
            if (check_prediction && c["cycle"].get<unsigned int>() == 1)
              AssertThrow(std::abs(obtained / predicted - 1) <= 0.25,
                          ExcMessage("remeshing missed N* by more than 25 %"));
          }
        out << std::endl;
      }
    const double epsilon = cycles.back()["epsilon"].get<double>();
    AssertThrow(epsilon <= target,
                ExcMessage("the loop did not reach epsilon_0"));
    AssertThrow(
      summary["stop_reason"].get<std::string>().rfind("target reached", 0) == 0,
      ExcMessage("the loop stopped for another reason"));
    AssertThrow(cycles.size() > 1, ExcMessage("nothing was adapted"));
    AssertThrow(max_adaptation_steps == 0 ||
                  cycles.size() - 1 <= max_adaptation_steps,
                ExcMessage("more adaptation steps than planned"));
    out << "    " << summary["stop_reason"].get<std::string>() << std::endl;
    // Within a tenth of the upper block's width (the initial cells are
    // 33 mm wide) for the graded triangles; a fifth for quadrilaterals,
    // whose finest level spreads over a patch of a few cells (one level
    // per cycle, 2:1 balance).
    if (check_finest)
      check_finest_cells(*run.problem,
                         run.parameters.adaptation.strategy ==
                             AdaptationStrategy::remesh ?
                           10 :
                           20,
                         out);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::setprecision(4);

  // Where the initial mesh's indicator density peaks: the contact zone ends.
  {
    auto settings =
      blocks("triangle", "uniform", "3, 3", "6, 7", "0", "output-density");
    settings.push_back({"Adaptation/Number of cycles", "1"});
    const ProgramRun      run(settings);
    const TwoBodyProblem &problem = *run.problem;
    const ErrorEstimate  &e       = problem.last_error_estimate();
    for (unsigned int b = 0; b < 2; ++b)
      {
        std::pair<double, double> best = {-1, 0}; // density, distance
        for (const auto &cell :
             problem.body(b).triangulation().active_cell_iterators())
          if (cell->is_locally_owned() &&
              e.density[b](cell->active_cell_index()) > best.first)
            best = {e.density[b](cell->active_cell_index()),
                    distance_to_contact_zone_ends(cell->center())};
        const auto all = Utilities::MPI::all_gather(MPI_COMM_WORLD, best);
        best           = *std::max_element(all.begin(), all.end());
        out << "Initial mesh, body " << b + 1 << ": largest epsilon_E density "
            << best.first << " /mm^2, cell centre " << best.second
            << " mm from a contact zone end" << std::endl;
        // Within half an initial cell (33 mm) of a contact zone end.
        AssertThrow(best.second < 15,
                    ExcMessage("density peak away from the contact edges"));
      }
  }

  out << "remesh, P1, epsilon_0 = 5 %" << std::endl;
  run_loop(blocks("triangle", "remesh", "2, 2", "4, 4", "5", "output-r5"),
           0.05,
           false,
           false,
           2,
           out);
  out << "remesh, P1, epsilon_0 = 2 %" << std::endl;
  run_loop(blocks("triangle", "remesh", "3, 3", "6, 7", "2", "output-r2"),
           0.02,
           true,
           true,
           2,
           out);
  out << "remesh, P1, epsilon_0 = 1 %" << std::endl;
  run_loop(blocks("triangle", "remesh", "3, 3", "6, 7", "1", "output-r1"),
           0.01,
           true,
           false,
           2,
           out);
  {
    out << "remesh (gmsh Delaunay), P1, epsilon_0 = 2 %" << std::endl;
    auto settings =
      blocks("triangle", "remesh", "3, 3", "6, 7", "2", "output-d2");
    settings.push_back({"Adaptation/Remeshing algorithm", "delaunay"});
    run_loop(settings, 0.02, true, true, 2, out);
  }
  out << "refine (size ratio), Q1, epsilon_0 = 5 %" << std::endl;
  run_loop(blocks("quadrilateral", "refine", "2, 2", "4, 4", "5", "output-q5"),
           0.05,
           false,
           false,
           2,
           out);
  out << "refine (size ratio), Q1, epsilon_0 = 2 %" << std::endl;
  run_loop(blocks("quadrilateral", "refine", "2, 2", "4, 4", "2", "output-q2"),
           0.02,
           true,
           false,
           2,
           out);
  {
    // cre's first plan from the coarse seed mesh lands below
    // 0.8 epsilon_0 (3.95 %: the convergence rate at the upper block's
    // corners is not yet what the plan assumes); with 'Over-refinement
    // ratio' the over-refined mesh is optimised again, coarser, and the
    // loop ends within [0.8, 1] epsilon_0 on fewer cells than the
    // overshoot.
    out << "remesh, P1, cre, epsilon_0 = 5 %, over-refinement ratio 0.8"
        << std::endl;
    auto settings =
      blocks("triangle", "remesh", "3, 3", "6, 7", "5", "output-cre-band");
    settings.push_back({"Error indicator/Estimator", "cre"});
    settings.push_back({"Adaptation/Over-refinement ratio", "0.8"});
    settings.push_back({"Adaptation/Number of cycles", "6"});
    const ProgramRun run(settings);
    const auto      &cycles     = run.summary["cycles"];
    unsigned int     most_cells = 0;
    for (const auto &c : cycles)
      {
        const unsigned int n_cells =
          c["bodies"][0]["n_cells"].get<unsigned int>() +
          c["bodies"][1]["n_cells"].get<unsigned int>();
        most_cells = std::max(most_cells, n_cells);
        out << "    cycle " << c["cycle"].get<unsigned int>() << ": cells "
            << n_cells << ", epsilon " << 100 * c["epsilon"].get<double>()
            << " %" << std::endl;
      }
    const double       epsilon = cycles.back()["epsilon"].get<double>();
    const unsigned int last_cells =
      cycles.back()["bodies"][0]["n_cells"].get<unsigned int>() +
      cycles.back()["bodies"][1]["n_cells"].get<unsigned int>();
    out << "    " << run.summary["stop_reason"].get<std::string>()
        << "; within [0.8, 1] epsilon_0: "
        << (epsilon >= 0.04 && epsilon <= 0.05 ? "yes" : "no")
        << ", fewer cells than the largest mesh: "
        << (last_cells < most_cells ? "yes" : "no") << std::endl;
    AssertThrow(epsilon >= 0.04 && epsilon <= 0.05 && last_cells < most_cells,
                ExcMessage("the over-refined mesh was not optimised again"));
  }
  for (const std::string min_cells : {"0", "100"})
    {
      // epsilon_0 far above reach, with 'Over-refinement ratio' (as in
      // prm/blocks.prm): every mesh is over-refined. Without a minimum the
      // remesh plans coarser meshes until gmsh's coarsest mesh of the
      // geometry (4 + 4 triangles), which a further plan returns unchanged.
      // The loop stops on the first repeat instead of solving that mesh
      // again on every cycle left (it solved cycles 4 to 10 on it). With the
      // default minimum of 100 cells it stops on the first mesh planned at
      // that minimum.
      out << "remesh, P1, epsilon_0 = 100 %, 12 cycles allowed, minimum "
          << min_cells << " cells" << std::endl;
      auto settings = blocks("triangle",
                             "remesh",
                             "3, 3",
                             "6, 7",
                             "100",
                             "output-r100-" + min_cells);
      settings.push_back({"Adaptation/Over-refinement ratio", "0.8"});
      settings.push_back({"Adaptation/Minimum number of cells", min_cells});
      const ProgramRun run(settings);
      const auto      &cycles  = run.summary["cycles"];
      unsigned int     repeats = 0;
      for (unsigned int c = 0; c < cycles.size(); ++c)
        {
          const auto n_cells = [&](const unsigned int b) {
            return cycles[c]["bodies"][b]["n_cells"].get<unsigned int>();
          };
          if (c > 0 &&
              n_cells(0) ==
                cycles[c - 1]["bodies"][0]["n_cells"].get<unsigned int>() &&
              n_cells(1) ==
                cycles[c - 1]["bodies"][1]["n_cells"].get<unsigned int>())
            ++repeats;
          out << "    cycle " << c << ": cells " << n_cells(0) << " + "
              << n_cells(1) << ", epsilon "
              << 100 * cycles[c]["epsilon"].get<double>() << " %" << std::endl;
        }
      out << "    " << run.summary["stop_reason"].get<std::string>()
          << std::endl;
      AssertThrow(repeats <= 1,
                  ExcMessage("the same mesh was solved again and again"));
      AssertThrow(run.summary["stop_reason"].get<std::string>().rfind(
                    "target reached", 0) == 0,
                  ExcMessage("the run did not stop on its target"));
      if (min_cells != "0")
        {
          const auto  &last = cycles.back();
          unsigned int n    = 0;
          for (unsigned int b = 0; b < 2; ++b)
            n += last["bodies"][b]["n_cells"].get<unsigned int>();
          out << "    last mesh at least " << min_cells
              << " cells: " << (n >= std::stoul(min_cells) ? "yes" : "no")
              << ", one remesh: " << (cycles.size() == 2 ? "yes" : "no")
              << std::endl;
          AssertThrow(n >= std::stoul(min_cells) && cycles.size() == 2,
                      ExcMessage(
                        "coarsened below the minimum number of cells"));
        }
    }
  for (const std::string strategy : {"refine", "remesh"})
    {
      out << strategy << ", epsilon_0 = 0.01 %, at most 3000 DoFs" << std::endl;
      auto settings =
        blocks(strategy == "refine" ? "quadrilateral" : "triangle",
               strategy,
               "2, 2",
               "4, 4",
               "0.01",
               "output-cap-" + strategy);
      settings.push_back({"Adaptation/Maximum number of DoFs", "3000"});
      settings.push_back({"Adaptation/Number of cycles", "4"});
      const ProgramRun run(settings);
      unsigned int     n_limited = 0;
      for (const auto &c : run.summary["cycles"])
        {
          const auto n_dofs = c["n_dofs"].get<unsigned int>();
          const bool limited =
            c.contains("adaptation") &&
            c["adaptation"]["limited_by_max_dofs"].get<bool>();
          n_limited += limited;
          out << "    cycle " << c["cycle"].get<unsigned int>() << ": DoFs "
              << n_dofs << (limited ? ", mesh limited by the cap" : "")
              << std::endl;
          AssertThrow(n_dofs <= 4 * 3000,
                      ExcMessage("an adapted mesh far above the DoF cap"));
        }
      AssertThrow(n_limited > 0, ExcMessage("the cap never acted"));
      // The log is rank 0's.
      AssertThrow(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) > 0 ||
                    run.log.str().find("more cells than 'Maximum number "
                                       "of DoFs'") != std::string::npos,
                  ExcMessage("the log does not say the mesh was limited"));
      out << "    " << run.summary["stop_reason"].get<std::string>()
          << std::endl;
    }
  {
    out << "refine (optimize), Q1, epsilon_0 = 2 %" << std::endl;
    auto settings =
      blocks("quadrilateral", "refine", "2, 2", "4, 4", "2", "output-o2");
    settings.push_back({"Adaptation/Refinement criterion", "optimize"});
    run_loop(settings, 0.02, false, false, 0, out);
  }
}
