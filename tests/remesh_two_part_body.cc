// A body made of two separate parts, remeshed: body 1 of
// tests/data/two_feet.geo is two feet, 40 mm wide, each loaded by 10 MPa on
// its top and standing on the lower block (mu = 0.3). Before, the remesher
// took the larger of the boundary loops as the outer boundary and the
// other foot's loop as a hole outside it, and stopped after cycle 0 with
// "a boundary node of gmsh's mesh is not a vertex of a triangle". Each
// part now becomes its own gmsh surface.
//
// Checked on every cycle, against each foot's own equilibrium (it touches
// nothing but its load and the lower block): the contact force on each
// foot, summed over its slave nodes from the contact CSV, is (0, 400) N/mm
// to 1e-10 relative; both feet carry slave nodes in contact after every
// remesh; the run reaches its target in remeshed cycles. 1 and 2 ranks
// print the same.

#include "program_run.h"

#include <fstream>
#include <sstream>

using namespace coulomb_adapt;

namespace
{
  struct FootForce
  {
    unsigned int nodes_in_contact = 0;
    double       normal = 0, tangential = 0;
  };

  // Sum of weight * traction over the slave nodes of each foot (x < 100:
  // the left one), from the cycle's contact CSV.
  std::array<FootForce, 2>
  foot_forces(const std::string &file_name)
  {
    std::ifstream file(file_name);
    AssertThrow(file, ExcMessage("cannot read " + file_name));
    std::string line;
    std::getline(file, line);
    AssertThrow(line.rfind("x,y,normal_x,normal_y,weight,contact_pressure,"
                           "tangential_traction,gap,slip,status",
                           0) == 0,
                ExcMessage("unexpected columns in " + file_name));
    std::array<FootForce, 2> feet;
    while (std::getline(file, line))
      {
        std::stringstream        row(line);
        std::string              cell;
        std::vector<std::string> cells;
        while (std::getline(row, cell, ','))
          cells.push_back(cell);
        FootForce   &foot   = feet[std::stod(cells[0]) < 100 ? 0 : 1];
        const double weight = std::stod(cells[4]);
        foot.normal += weight * std::stod(cells[5]);
        foot.tangential += weight * std::stod(cells[6]);
        if (cells[9] != "open")
          ++foot.nodes_in_contact;
      }
    return feet;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  testing::ProgramRun run(
    {{"Scene/Gmsh/Mesh file",
      std::string(COULOMB_ADAPT_TEST_DATA_DIR) + "/two_feet.geo"},
     {"Adaptation/Strategy", "remesh"},
     {"Adaptation/Target error", "2"},
     {"Adaptation/Number of cycles", "4"},
     {"Output/Write VTU", "false"},
     {"Output/Output directory", "remesh_two_part_body_files"}},
    testing::example_file("gmsh_blocks.prm"));

  const auto &cycles = run.summary["cycles"];
  AssertThrow(cycles.size() >= 2,
              ExcMessage("no remeshed cycle ran: " +
                         run.summary["stop_reason"].get<std::string>()));
  const double load = 40 * 10; // N/mm on each foot
  for (const auto &cycle : cycles)
    {
      const unsigned int c    = cycle["cycle"].get<unsigned int>();
      const auto         feet = foot_forces(run.parameters.output.directory +
                                    "/contact_00" + std::to_string(c) + ".csv");
      out << "cycle " << c << " (" << cycle["strategy"].get<std::string>()
          << "): " << cycle["n_dofs"].get<unsigned long>() << " DoFs, eps "
          << std::fixed << std::setprecision(3)
          << 100 * cycle["epsilon"].get<double>() << " %" << std::endl;
      for (unsigned int f = 0; f < 2; ++f)
        {
          const double normal_error     = std::abs(feet[f].normal / load - 1);
          const double tangential_error = std::abs(feet[f].tangential / load);
          out << "  " << (f == 0 ? "left" : "right")
              << " foot: nodes in contact > 0: "
              << (feet[f].nodes_in_contact > 0 ? "yes" : "no")
              << ", |F_n / 400 - 1| < 1e-10: "
              << (normal_error < 1e-10 ? "yes" : "no")
              << ", |F_t| / 400 < 1e-10: "
              << (tangential_error < 1e-10 ? "yes" : "no") << std::endl;
          AssertThrow(feet[f].nodes_in_contact > 0 && normal_error < 1e-10 &&
                        tangential_error < 1e-10,
                      ExcMessage("foot " + std::to_string(f) + " of cycle " +
                                 std::to_string(c) + ": normal force " +
                                 std::to_string(feet[f].normal) +
                                 ", tangential force " +
                                 std::to_string(feet[f].tangential)));
        }
    }
  out << "stop: " << run.summary["stop_reason"].get<std::string>() << std::endl;
}
