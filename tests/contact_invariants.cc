// Invariants of the static contact solution on the seed's blocks (quads
// and triangles, mu = 0.3, upper block held by friction alone):
//  - equilibrium: contact force = applied load (1e-8 relative);
//  - homogeneity: loads x 1e-3 and x 1e3 scale displacements and
//    multipliers exactly (1e-8), with the same sets;
//  - c_n, c_t x 100 and / 100: the same solution (1e-8);
//  - mirror symmetry about x = 100: pressure symmetric, tangential
//    traction antisymmetric (1e-8 of the largest pressure);
//  - Newton converges within 10 steps.
// Run on 1 and 2 ranks with the same output.

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

struct Snapshot
{
  std::vector<ContactNodeState> states;
  double                        u1_norm;
  std::string                   sets;
};

Snapshot
run(const std::string &cell_type,
    const std::string &pressure,
    const std::string &scale)
{
  const auto problem =
    testing::solve_contact({{"Scene/Name", "blocks"},
                            {"Mesh/Cell type", cell_type},
                            {"Mesh/Global refinements", "2"},
                            {"Scene/Blocks/Pressure", pressure},
                            {"Contact/Complementarity scale", scale}});
  Snapshot s;
  s.states = problem->solver->node_states();
  // (l2_norm() of a ghosted vector is not defined in parallel.)
  double squares = 0;
  for (const auto i : problem->bodies[0]->locally_owned_dof_set())
    squares += std::pow(problem->bodies[0]->solution()[i], 2);
  s.u1_norm = std::sqrt(Utilities::MPI::sum(squares, MPI_COMM_WORLD));
  for (const auto &n : s.states)
    s.sets += to_string(n.status)[0];
  const double       p = std::stod(pressure);
  const Tensor<1, 2> applied({0., -p * 100.});
  const double       imbalance =
    (problem->report.contact_force + applied).norm() / applied.norm();
  AssertThrow(imbalance < 1e-8,
              ExcMessage("imbalance " + std::to_string(imbalance)));
  AssertThrow(problem->report.newton_iterations <= 10,
              ExcMessage("Newton steps: " +
                         std::to_string(problem->report.newton_iterations)));
  return s;
}

// Largest difference of pressures and tangential tractions of b * factor
// against a, relative to a's largest pressure.
double
difference(const Snapshot &a, const Snapshot &b, const double factor)
{
  double p = 0, d = 0;
  for (unsigned int j = 0; j < a.states.size(); ++j)
    {
      p = std::max(p, a.states[j].pressure);
      d = std::max(
        {d,
         std::abs(a.states[j].pressure - factor * b.states[j].pressure),
         std::abs(a.states[j].tangential_traction -
                  factor * b.states[j].tangential_traction)});
    }
  return d / p;
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  for (const std::string cell_type : {"quadrilateral", "triangle"})
    {
      const Snapshot base    = run(cell_type, "10", "1");
      unsigned int   n_stick = 0, n_slip = 0;
      for (const auto &s : base.states)
        {
          n_stick += s.status == ContactStatus::stick;
          n_slip += s.status == ContactStatus::slip;
        }
      out << "blocks, " << cell_type << ": " << base.states.size()
          << " slave nodes, " << n_stick << " stick, " << n_slip
          << " slip; equilibrium to 1e-8 and <= 10 Newton steps: yes"
          << std::endl;

      for (const double factor : {1e-3, 1e3})
        {
          std::ostringstream p;
          p << 10 * factor;
          const Snapshot scaled = run(cell_type, p.str(), "1");
          const double   d      = difference(base, scaled, 1. / factor);
          const double   du =
            std::abs(scaled.u1_norm / factor - base.u1_norm) / base.u1_norm;
          out << "  loads x " << factor
              << ": same sets: " << (scaled.sets == base.sets ? "yes" : "no")
              << ", multipliers and displacements scale to 1e-8: "
              << (d < 1e-8 && du < 1e-8 ? "yes" : "no") << std::endl;
          AssertThrow(scaled.sets == base.sets && d < 1e-8 && du < 1e-8,
                      ExcMessage("homogeneity: " + std::to_string(d) + ", " +
                                 std::to_string(du)));
        }

      for (const std::string scale : {"100", "0.01"})
        {
          const Snapshot other = run(cell_type, "10", scale);
          const double   d     = difference(base, other, 1.);
          const double   du =
            std::abs(other.u1_norm - base.u1_norm) / base.u1_norm;
          out << "  complementarity scale " << scale
              << ": same solution to 1e-8: "
              << (d < 1e-8 && du < 1e-8 && other.sets == base.sets ? "yes" :
                                                                     "no")
              << std::endl;
          AssertThrow(d < 1e-8 && du < 1e-8 && other.sets == base.sets,
                      ExcMessage("scale dependence: " + std::to_string(d)));
        }

      // Mirror symmetry: node j and node n-1-j (sorted along x).
      double      p = 0, asymmetry = 0;
      const auto &s = base.states;
      const auto  n = s.size();
      for (unsigned int j = 0; j < n; ++j)
        {
          p = std::max(p, s[j].pressure);
          AssertThrow(std::abs(s[j].position[0] + s[n - 1 - j].position[0] -
                               200) < 1e-10,
                      ExcMessage("slave nodes not symmetric"));
          asymmetry = std::max({asymmetry,
                                std::abs(s[j].pressure - s[n - 1 - j].pressure),
                                std::abs(s[j].tangential_traction +
                                         s[n - 1 - j].tangential_traction)});
        }
      out << "  mirror symmetry about x = 100 to 1e-8: "
          << (asymmetry < 1e-8 * p ? "yes" : "no") << std::endl;
      AssertThrow(asymmetry < 1e-8 * p,
                  ExcMessage("asymmetry " + std::to_string(asymmetry / p)));

      // The numbers themselves, for the comparison with the stored output
      // (and between 1 and 2 ranks).
      out << "  pressure at the centre and at the edges (MPa): "
          << std::setprecision(6) << s[n / 2].pressure << " " << s[0].pressure
          << " " << s[n - 1].pressure << std::endl;
    }
}
