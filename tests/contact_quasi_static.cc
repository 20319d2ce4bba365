// Quasi-static Coulomb contact between dissimilar bodies: cattaneo (the
// Hertz disc indented in load step 1, then pushed sideways) with body 1 at
// nu = 0.1, so that the interface slips already under the normal load.
//  1. The default path (5 tangential steps) and a single tangential step:
//     at c = E_c/D the active set iteration cycles in the tangential steps;
//     the solver reduces c (damping) and converges. Checked: every
//     traction in the Coulomb cone, every slip node on its edge (1e-8 of
//     the largest pressure).
//  2. A second load step that adds no load: every slip node of step 1 sits
//     on the cone's edge with no slip increment, where stick and slip are
//     the same state; the iteration must converge (round-off used to make
//     the sets flip for ever), and the indicator must see the slip of this
//     step, zero at every node (1e-12 mm), not the total slip of the run
//     (above 1e-6 mm at some node).
// 1 and 2 ranks.

#include <coulomb_adapt/app/two_body_problem.h>

#include "test_utilities.h"

#include <fstream>
#include <sstream>

using namespace coulomb_adapt;

namespace
{
  const std::string output_directory = "/tmp/coulomb-adapt-test-quasi-static";

  struct NodeRow
  {
    double      pressure, traction, slip;
    std::string status;
  };

  // The run's contact CSV (rank 0 writes it).
  std::vector<NodeRow>
  read_contact_csv()
  {
    std::ifstream in(output_directory + "/contact_000.csv");
    std::string   line;
    std::getline(in, line); // x,y,normal_x,normal_y,weight,contact_pressure,
                            // tangential_traction,gap,slip,status,...
    std::vector<NodeRow> rows;
    while (std::getline(in, line))
      {
        std::vector<std::string> c;
        std::stringstream        s(line);
        for (std::string v; std::getline(s, v, ',');)
          c.push_back(v);
        rows.push_back({std::stod(c.at(5)),
                        std::stod(c.at(6)),
                        std::stod(c.at(8)),
                        c.at(9)});
      }
    return rows;
  }

  void
  run(const std::string  &tangential_displacement,
      const std::string  &tangential_steps,
      ConditionalOStream &out)
  {
    ParameterHandler prm;
    const Parameters parameters = testing::make_parameters(
      prm,
      {{"Scene/Name", "cattaneo"},
       {"Scene/Hertz/Body 1/Poisson's ratio", "0.1"},
       {"Scene/Cattaneo/Tangential displacement", tangential_displacement},
       {"Scene/Cattaneo/Tangential load steps", tangential_steps},
       {"Adaptation/Number of cycles", "1"},
       // The load steps from the step before's sets, where the damping is
       // needed: started from the coarser meshes' path (nested iteration,
       // the default) the sets do not cycle and c is not reduced.
       {"Contact/Nested iteration levels", "0"},
       {"Output/Write VTU", "false"},
       {"Output/Output directory", output_directory}});
    prepare_output_directory(output_directory, MPI_COMM_WORLD);
    std::ostringstream log;
    TwoBodyProblem     problem(MPI_COMM_WORLD, parameters, prm, "test", log);
    problem.run(); // throws with a diagnosis if it does not converge
    const ErrorEstimate &e = problem.last_error_estimate();
    const bool           damped =
      log.str().find("damped set changes") != std::string::npos;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;

    const double mu    = 0.3;
    const auto   rows  = read_contact_csv();
    double       p_max = 0, cone = 0, edge = 0, total_slip = 0;
    unsigned int n_stick = 0, n_slip = 0;
    for (const auto &r : rows)
      p_max = std::max(p_max, r.pressure);
    for (const auto &r : rows)
      {
        cone = std::max(cone, std::abs(r.traction) - mu * r.pressure);
        if (r.status == "slip")
          {
            ++n_slip;
            edge =
              std::max(edge, std::abs(std::abs(r.traction) - mu * r.pressure));
          }
        n_stick += (r.status == "stick");
        if (r.status != "open")
          total_slip = std::max(total_slip, std::abs(r.slip));
      }
    AssertThrow(cone <= 1e-8 * p_max,
                ExcMessage("traction outside the cone: " +
                           std::to_string(cone)));
    AssertThrow(edge <= 1e-8 * p_max,
                ExcMessage("slip node off the cone's edge: " +
                           std::to_string(edge)));
    double increment = 0;
    for (const auto &f : e.correction.fields)
      increment = std::max(increment, std::abs(f.slip));

    out << "tangential displacement " << tangential_displacement << " mm in "
        << tangential_steps << " step(s): " << n_stick << " stick, " << n_slip
        << " slip nodes; tractions in the cone, slip nodes on its edge (1e-8); "
        << (damped ? "c reduced" : "c not reduced");
    if (std::stod(tangential_displacement) == 0)
      {
        AssertThrow(total_slip > 1e-6,
                    ExcMessage("no slip in step 1: the check would be void"));
        AssertThrow(increment < 1e-12,
                    ExcMessage("the indicator sees a slip of " +
                               std::to_string(increment) +
                               " mm in a step without load"));
        out << "; slip of the last step seen by the indicator below 1e-12 mm, "
               "total slip above 1e-6 mm";
      }
    out << std::endl;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  run("0.011", "5", out);
  run("0.011", "1", out);
  run("0", "1", out);
}
