// Press (shrink) fit, theory.md section 9, run from prm/press_fit.prm (the
// gmsh scene with per-group conditions): a quarter of a solid shaft
// (radius b = 10 mm) in a hub (bore b - delta, outer radius c = 20 mm),
// rollers on the symmetry lines, frictionless, E = 200 000 MPa, nu = 0.3,
// plane strain. The bodies start overlapping by delta = 0.001 mm: the
// mortar's weighted gap is negative at every node, every node is active,
// and the contact pressure is Lame's uniform
//   p = E delta (c^2 - b^2) / (2 b c^2 (1 - nu^2)).
// Checked: the initial overlap (delta) and clearance (0) the interface
// reports, every node in contact, the nodal pressures' largest deviation
// from p within 1 % (P1 on the file's mesh with half its element sizes, P2
// on the file's mesh) and their mean over the bore within 1e-3 (P1) and
// 1e-4 (P2).
//
// What limits P2 is the straight-sided mesh: the circles are polygons, and
// the pressure between two parallel polygons is higher at their corners.
// The vertex and mid-edge pressures alternate by +-0.5 % at this size, half
// of that at half the size (largest deviation 0.76 %, 0.38 %, 0.20 % at
// Mesh size factor 1, 0.5, 0.25; the last takes 30 s, too long for the
// suite). The difference between b and b - delta in Lame's formula is
// 1e-4 relative.

#include <coulomb_adapt/scenes/gmsh_file.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const std::string root = std::string(COULOMB_ADAPT_TEST_DATA_DIR) + "/../..";
  const double      E = 200000, nu = 0.3, b = 10, c = 20, delta = 0.001;
  const double      lame =
    E * delta * (c * c - b * b) / (2 * b * c * c * (1 - nu * nu));
  out << "Lame's pressure p = " << std::setprecision(6) << lame << " MPa"
      << std::endl;

  struct Case
  {
    std::string degree, size_factor;
    double      tolerance, mean_tolerance;
  };
  for (const Case &test :
       {Case{"1", "0.5", 0.01, 1e-3}, Case{"2", "1", 0.01, 1e-4}})
    {
      const auto problem = testing::solve_contact(
        {{"Scene/Gmsh/Mesh file", root + "/prm/meshes/press_fit.geo"},
         {"Scene/Gmsh/Mesh size factor", test.size_factor},
         {"Finite elements/Polynomial degree", test.degree}},
        root + "/prm/press_fit.prm");

      // The initial gap as the mortar integrates it, per slave node.
      const MortarInterface &mortar  = problem->solver->mortar_interface();
      double                 overlap = 0, clearance = 0;
      unsigned int           n_covered = 0;
      for (unsigned int j = 0; j < mortar.slave_nodes().size(); ++j)
        if (mortar.is_covered(j))
          {
            ++n_covered;
            const double g =
              mortar.weighted_initial_gaps()[j] / mortar.slave_weights()[j];
            overlap   = std::max(overlap, -g);
            clearance = std::max(clearance, g);
          }

      // The nodal pressures, and their mean over the bore (the contact
      // force's magnitude over the bore's length).
      double       deviation = 0, lowest = 1e300, highest = 0;
      double       force = 0, length = 0;
      unsigned int n_active = 0;
      for (const auto &s : problem->solver->node_states())
        {
          n_active += s.status != ContactStatus::open;
          force += s.pressure * s.weight;
          length += s.weight;
          deviation = std::max(deviation, std::abs(s.pressure - lame) / lame);
          lowest    = std::min(lowest, s.pressure);
          highest   = std::max(highest, s.pressure);
        }
      const unsigned int n_nodes        = problem->solver->node_states().size();
      const double       mean_deviation = force / length / lame - 1;

      out << "P" << test.degree << ", Mesh size factor " << test.size_factor
          << ": " << n_nodes << " slave nodes, " << n_covered
          << " facing the shaft, " << n_active << " in contact" << std::endl
          << "  initial overlap / delta = " << std::setprecision(4)
          << overlap / delta << ", clearance = " << clearance << " mm"
          << std::endl
          << "  pressure / p in [" << std::setprecision(5) << lowest / lame
          << ", " << highest / lame << "], largest deviation "
          << std::setprecision(2) << 100 * deviation << " % (within "
          << 100 * test.tolerance
          << " %: " << (deviation < test.tolerance ? "yes" : "no") << ")"
          << std::endl
          << "  mean pressure / p - 1 = " << std::setprecision(1)
          << std::scientific << mean_deviation << std::defaultfloat
          << " (within " << test.mean_tolerance << ": "
          << (std::abs(mean_deviation) < test.mean_tolerance ? "yes" : "no")
          << ")" << std::endl;
      AssertThrow(n_covered == n_nodes && n_active == n_nodes,
                  ExcMessage("not every node of the bore is in contact"));
      AssertThrow(std::abs(overlap / delta - 1) < 1e-3 && clearance == 0,
                  ExcMessage("initial overlap " + std::to_string(overlap) +
                             ", clearance " + std::to_string(clearance)));
      AssertThrow(deviation < test.tolerance &&
                    std::abs(mean_deviation) < test.mean_tolerance,
                  ExcMessage("pressure off Lame's by " +
                             std::to_string(deviation) + ", mean by " +
                             std::to_string(mean_deviation)));
    }
}
