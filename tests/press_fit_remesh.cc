// The press fit of prm/press_fit.prm (P2, Mesh size factor 1) adapted with
// Strategy = remesh: the hub is an annulus (a body with a hole) and both
// bodies are held at physical points, two inside the shaft. Checked on the
// remeshed cycle: it runs (before: "remeshing body 1 failed", the remesher
// took one boundary curve), the point supports are nodes of the new meshes
// (else the run stops: a support that selects no node is an error), and
// the circles stayed circles: the initial overlap the mortar integrates is
// the interference delta within 1e-3 at every node and there is no
// clearance (remeshed as polygons of the coarse vertices the gap would be
// off by the sag of their arcs, h^2 / (8 r), several delta); every slave
// node is in contact, and the contact forces cancel (uniform pressure).

#include "program_run.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const double        delta = 0.001;
  testing::ProgramRun run(
    {{"Scene/Gmsh/Mesh file", testing::example_file("meshes/press_fit.geo")},
     {"Adaptation/Strategy", "remesh"},
     {"Adaptation/Target error", "0.02"},
     {"Adaptation/Number of cycles", "2"},
     {"Output/Output directory", "press_fit_remesh_files"}},
    testing::example_file("press_fit.prm"));

  const auto &cycles = run.summary["cycles"];
  AssertThrow(cycles.size() == 2,
              ExcMessage("the remeshed cycle did not run: " +
                         run.summary["stop_reason"].get<std::string>()));
  for (const auto &cycle : cycles)
    {
      const double overlap   = cycle["initial_overlap"].get<double>();
      const double clearance = cycle["initial_clearance"].get<double>();
      const double force = std::hypot(cycle["contact_force"][0].get<double>(),
                                      cycle["contact_force"][1].get<double>());
      const unsigned int active = cycle["active_nodes"].get<unsigned int>();
      // The slave nodes: the rows of the cycle's contact file.
      const unsigned int c = cycle["cycle"].get<unsigned int>();
      std::ifstream      file(run.parameters.output.directory + "/contact_00" +
                         std::to_string(c) + ".csv");
      std::string        line;
      unsigned int       slave_nodes = 0;
      std::getline(file, line);
      while (std::getline(file, line))
        ++slave_nodes;
      out
        << "cycle " << cycle["cycle"].get<unsigned int>() << " ("
        << cycle["strategy"].get<std::string>()
        << "): " << cycle["n_dofs"].get<unsigned long>() << " DoFs, " << active
        << " of " << slave_nodes
        << " slave nodes in contact, initial overlap / delta - 1 within 1e-3: "
        << (std::abs(overlap / delta - 1) < 1e-3 ? "yes" : "no")
        << ", clearance " << clearance
        << ", |contact force| < 0.01 N/mm: " << (force < 0.01 ? "yes" : "no")
        << std::endl;
      AssertThrow(std::abs(overlap / delta - 1) < 1e-3 && clearance == 0 &&
                    active == slave_nodes && force < 0.01,
                  ExcMessage("remeshed press fit: overlap " +
                             std::to_string(overlap) + ", clearance " +
                             std::to_string(clearance) + ", force " +
                             std::to_string(force)));
    }
}
