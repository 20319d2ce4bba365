// Hertz line contact (theory.md section 6), half disc on a block, with the
// meshes graded to 20 elements across the contact width and then refined
// uniformly once:
//  - frictionless: peak pressure p0 and half-width a within 2 % of
//    Hertz's, a from a least-squares fit of p^2 = p0^2 (1 - x^2 / a^2) to
//    the nodal pressures; the L2 error of the pressure profile decreases
//    under refinement;
//  - identical materials, mu = 0.3: the frictionless pressure (within
//    0.5 % of p0) and almost no tangential traction (below 1 % of p0 on
//    |x| < a/2). Hertz's "friction has no effect" holds for two
//    half-spaces; here the disc and the block are finite, loaded and
//    supported differently, so their far-field lateral strains differ by
//    about 1e-5, which friction resists with tractions of about 1 % of p0;
//    the last nodes before the contact edge slip;
//  - equilibrium: contact force = applied load (1e-8 relative).

#include <coulomb_adapt/scenes/hertz.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

struct HertzNumbers
{
  double              peak, half_width, l2_error;
  std::vector<double> pressures;
  double              max_tangential;
};

HertzNumbers
evaluate(const testing::SolvedContactProblem &problem)
{
  const auto  &hertz = dynamic_cast<const scenes::Hertz &>(*problem.scene);
  const double a = hertz.contact_half_width(), p0 = hertz.peak_pressure();
  HertzNumbers n{0, 0, 0, {}, 0};
  // Least squares for p^2 = c0 + c1 x^2 over the active nodes.
  double error2 = 0, norm2 = 0;
  for (const auto &s : problem.solver->node_states())
    {
      const double x = s.position[0];
      n.pressures.push_back(s.pressure);
      n.peak = std::max(n.peak, s.pressure);
      if (std::abs(x) < 0.5 * a)
        n.max_tangential =
          std::max(n.max_tangential, std::abs(s.tangential_traction));
      const double exact =
        std::abs(x) < a ? p0 * std::sqrt(1 - x * x / (a * a)) : 0;
      error2 += s.weight * std::pow(s.pressure - exact, 2);
      norm2 += s.weight * exact * exact;
    }
  n.half_width = testing::fitted_half_width(problem.solver->node_states());
  n.l2_error   = std::sqrt(error2 / norm2);
  return n;
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  std::vector<double> l2_errors;
  for (const std::string refinements : {"0", "1"})
    {
      const auto frictionless =
        testing::solve_contact({{"Scene/Name", "hertz"},
                                {"Mesh/Global refinements", refinements},
                                {"Contact/Friction coefficient", "0"}});
      const auto &hertz =
        dynamic_cast<const scenes::Hertz &>(*frictionless->scene);
      const double a = hertz.contact_half_width(), p0 = hertz.peak_pressure();
      const HertzNumbers h = evaluate(*frictionless);
      l2_errors.push_back(h.l2_error);

      const double peak_error  = std::abs(h.peak - p0) / p0;
      const double width_error = std::abs(h.half_width - a) / a;
      const double imbalance =
        (frictionless->report.contact_force + Tensor<1, 2>({0., -1000.}))
          .norm() /
        1000.;
      out << "hertz, " << refinements
          << " global refinement(s), mu = 0: " << frictionless->report.n_active
          << " active nodes" << std::endl
          << "  p0 within 2 %: " << (peak_error < 0.02 ? "yes" : "no")
          << ", a within 2 %: " << (width_error < 0.02 ? "yes" : "no")
          << ", equilibrium to 1e-8: " << (imbalance < 1e-8 ? "yes" : "no")
          << std::endl;
      AssertThrow(peak_error < 0.02 && width_error < 0.02 && imbalance < 1e-8,
                  ExcMessage("Hertz: p0 error " + std::to_string(peak_error) +
                             ", a error " + std::to_string(width_error) +
                             ", imbalance " + std::to_string(imbalance)));

      const auto friction =
        testing::solve_contact({{"Scene/Name", "hertz"},
                                {"Mesh/Global refinements", refinements},
                                {"Contact/Friction coefficient", "0.3"}});
      const HertzNumbers f          = evaluate(*friction);
      double             difference = 0;
      for (unsigned int j = 0; j < f.pressures.size(); ++j)
        difference =
          std::max(difference, std::abs(f.pressures[j] - h.pressures[j]));
      out << "  mu = 0.3, identical materials: pressure = frictionless "
             "within 5e-3 p0: "
          << (difference < 5e-3 * p0 ? "yes" : "no")
          << ", |tangential traction| < 1e-2 p0 on |x| < a/2: "
          << (f.max_tangential < 1e-2 * p0 ? "yes" : "no") << std::endl;
      AssertThrow(difference < 5e-3 * p0 && f.max_tangential < 1e-2 * p0,
                  ExcMessage("friction changes Hertz: " +
                             std::to_string(difference / p0) + ", " +
                             std::to_string(f.max_tangential / p0)));
    }
  out << "L2 error of the pressure decreases under refinement: "
      << (l2_errors[1] < l2_errors[0] ? "yes" : "no") << std::endl;
  AssertThrow(l2_errors[1] < l2_errors[0], ExcMessage("no convergence"));
}
