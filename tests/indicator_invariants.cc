// The error indicator against what must hold whatever the mesh:
//  - contact patch test (uniform stress, non-matching meshes, Q1 and P1,
//    with and without friction): epsilon^2 = 0 to round-off;
//  - epsilon^2 = sum of epsilon_E^2 over the cells of both bodies, where
//    the global value counts the contact term as 2 int c (3-10) and the
//    cells receive it from both sides: blocks, hertz, punch;
//  - homogeneity: loads x 1e-3 and x 1e3 leave epsilon and every
//    epsilon_E unchanged (zero initial gap: blocks, punch);
//  - the seed's example on about 398 P1 triangles: epsilon within the
//    4-10 % band around the seed's 6.58 % (theory.md section 5).

#include <coulomb_adapt/indicator/error_estimate.h>

#include "contact_test_utilities.h"

#include <cmath>
#include <iomanip>

using namespace coulomb_adapt;

namespace
{
  ErrorEstimate
  estimate(const testing::SolvedContactProblem &p)
  {
    return estimate_error({{p.bodies[0].get(), p.bodies[1].get()}},
                          p.solver.get(),
                          p.parameters.contact.friction_coefficient,
                          StressRecoveryMethod::l2_projection,
                          p.parameters.linear_solver);
  }

  // sum over the locally owned cells of both bodies, over all ranks.
  double
  sum_of_squared_indicators(const ErrorEstimate &e)
  {
    double sum = 0;
    for (unsigned int b = 0; b < 2; ++b)
      sum += e.contribution_squared[b].l1_norm();
    return Utilities::MPI::sum(sum, MPI_COMM_WORLD) / e.normalisation_squared;
  }

} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::setprecision(4);

  out << "Contact patch test: epsilon = 0" << std::endl;
  for (const std::string cell_type : {"quadrilateral", "triangle"})
    for (const std::string mu : {"0", "0.3"})
      {
        const auto p = testing::solve_contact(
          {{"Scene/Name", "patch"},
           {"Mesh/Cell type", cell_type},
           {"Scene/Patch/Pressure", "2.5"},
           {"Scene/Patch/Upper body subdivisions", "3, 2"},
           {"Scene/Patch/Lower body subdivisions", "10, 4"},
           {"Contact/Friction coefficient", mu}});
        const ErrorEstimate e = estimate(*p);
        // epsilon^2 is what is linear in the round-off of the fields (the
        // contact term is a product of a traction and a jump of ~1e-16
        // relative size): it must vanish to round-off.
        const double epsilon_squared = e.epsilon * e.epsilon;
        out << "  " << cell_type << ", mu = " << mu << ": epsilon^2 < 1e-13: "
            << (epsilon_squared < 1e-13 ? "yes" : "no")
            << ", correction skipped: " << (e.correction.skipped ? "yes" : "no")
            << std::endl;
        AssertThrow(epsilon_squared < 1e-13,
                    ExcMessage("patch test: epsilon^2 = " +
                               std::to_string(epsilon_squared)));
      }

  out << "epsilon^2 = sum epsilon_E^2" << std::endl;
  const std::vector<
    std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>
    scenes = {{"blocks (P1, mu = 0.3)",
               {{"Scene/Name", "blocks"},
                {"Mesh/Cell type", "triangle"},
                {"Contact/Friction coefficient", "0.3"}}},
              {"hertz (Q1, mu = 0)",
               {{"Scene/Name", "hertz"},
                {"Scene/Hertz/Contact mesh size", "0.3"},
                {"Contact/Friction coefficient", "0"}}},
              {"punch (Q1, mu = 0.3)",
               {{"Scene/Name", "punch"},
                {"Contact/Friction coefficient", "0.3"}}}};
  for (const auto &[name, settings] : scenes)
    {
      const auto          p   = testing::solve_contact(settings);
      const ErrorEstimate e   = estimate(*p);
      const double        sum = sum_of_squared_indicators(e);
      const double        mismatch =
        std::abs(sum - e.epsilon * e.epsilon) / (e.epsilon * e.epsilon);
      out << "  " << name << ": epsilon = " << std::fixed
          << std::setprecision(3) << 100 * e.epsilon << " %, contact part "
          << 100 * e.epsilon_contact << std::defaultfloat
          << std::setprecision(4)
          << " %, |sum - epsilon^2| / epsilon^2 < 1e-12: "
          << (mismatch < 1e-12 ? "yes" : "no") << std::endl;
      AssertThrow(mismatch < 1e-12, ExcMessage(name + ": sum rule broken"));
    }

  out << "Homogeneity: loads x 1e-3 and x 1e3" << std::endl;
  const std::vector<
    std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>
    homogeneous = {{"blocks",
                    {{"Scene/Name", "blocks"},
                     {"Mesh/Cell type", "triangle"},
                     {"Contact/Friction coefficient", "0.3"}}},
                   {"punch",
                    {{"Scene/Name", "punch"},
                     {"Contact/Friction coefficient", "0.3"}}}};
  for (const auto &[name, settings] : homogeneous)
    {
      const std::string load_entry =
        name == "blocks" ? "Scene/Blocks/Pressure" : "Scene/Punch/Pressure";
      const double base_load = name == "blocks" ? 10 : 100;
      auto         with_load = [&](const double factor) {
        auto s = settings;
        s.emplace_back(load_entry, std::to_string(base_load * factor));
        return s;
      };
      const auto          p0        = testing::solve_contact(with_load(1));
      const ErrorEstimate e0        = estimate(*p0);
      const auto          reference = testing::gathered_indicators(
        {{p0->bodies[0].get(), p0->bodies[1].get()}}, e0);
      for (const double factor : {1e-3, 1e3})
        {
          const auto          p = testing::solve_contact(with_load(factor));
          const ErrorEstimate e = estimate(*p);
          const auto          indicators = testing::gathered_indicators(
            {{p->bodies[0].get(), p->bodies[1].get()}}, e);
          double largest = 0, difference = 0;
          for (unsigned int i = 0; i < indicators.size(); ++i)
            {
              largest = std::max(largest, reference[i]);
              difference =
                std::max(difference, std::abs(indicators[i] - reference[i]));
            }
          const bool same_epsilon =
            std::abs(e.epsilon - e0.epsilon) <= 1e-10 * e0.epsilon;
          const bool same_cells = difference <= 1e-10 * largest;
          out << "  " << name << " x " << factor
              << ": epsilon unchanged to 1e-10: "
              << (same_epsilon ? "yes" : "no")
              << ", every epsilon_E unchanged to 1e-10 of the largest: "
              << (same_cells ? "yes" : "no") << std::endl;
          AssertThrow(same_epsilon && same_cells,
                      ExcMessage(name + ": indicator not homogeneous"));
        }
    }

  {
    // 3 x 3 and 6 x 7 quads, 8 triangles each: 72 + 336 = 408 triangles.
    const auto p =
      testing::solve_contact({{"Scene/Name", "blocks"},
                              {"Mesh/Cell type", "triangle"},
                              {"Scene/Blocks/Upper body subdivisions", "3, 3"},
                              {"Scene/Blocks/Lower body subdivisions", "6, 7"},
                              {"Contact/Friction coefficient", "0.3"}});
    const ErrorEstimate e = estimate(*p);
    const auto n_cells = p->bodies[0]->triangulation().n_global_active_cells() +
                         p->bodies[1]->triangulation().n_global_active_cells();
    out << "Seed's example: " << n_cells
        << " P1 triangles, epsilon = " << std::fixed << std::setprecision(2)
        << 100 * e.epsilon << " % (seed: 398 triangles, 6.58 %)" << std::endl;
    AssertThrow(e.epsilon > 0.04 && e.epsilon < 0.10,
                ExcMessage("seed's example: epsilon outside 4-10 %"));
  }
}
