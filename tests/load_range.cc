// Loads at the ends of the range of doubles (issue 21):
//  - blocks with pressures 1e-110 and 1e110 give the epsilon of pressure
//    1 to 1e-12 (the first cases of the test, kept; before the accepted
//    range 1e152 gave 100 % with exit 0);
//  - where stresses, moduli, strains and energy densities are within
//    1e-30 ... 1e30 (core/units.h) the problem is solved as given
//    (summary.json has no load_scale for pressure 1); beyond, the
//    static problem with zero initial gap is positively
//    homogeneous (theory.md section 6), so it is solved with the loads
//    divided by a power of 2 (core/units.h): pressures 1e-300 ... 1e300
//    give the epsilon, every epsilon_E, the DoFs and the contact sets of
//    each cycle of pressure 1 to 1e-12, and the contact force scales with
//    the pressure (before: 1e200 gave epsilon = nan, 1e-300 epsilon = 0
//    and "target reached", both with exit 0; then a NonFiniteResult after
//    the solve); energies that are no doubles (1e600) are reported scaled
//    and listed in summary.json, which holds no null;
//  - moduli times 1e100 and 1e-100 with the loads alike give the same
//    (divided together by a power of 2);
//    so do moduli times 1e+-200 and 1e+-300 with the loads alike (moduli
//    and loads divided together), and moduli alone times 1e+-150 and
//    1e+-250 (strains of 1e-253 ... 1e148: displacements scaled too);
//    strains beyond 1e+-300 stop before the solve;
//  - manufactured (no contact) with amplitudes 1e-300 and 1e200: the
//    epsilon, epsilon_E, DoFs and relative exact error of amplitude 1;
//  - hertz (an initial gap) with line load and moduli times 1.1e40: both
//    divided by a power of 2, displacements as given, the same solution;
//  - with an initial gap (hertz) the problem is not homogeneous: line
//    load 1e-200 stops before the solve, on every rank, with a message
//    naming the scene's load entry and the gap; 1e200 stops earlier, when
//    the scene reads it, for its Hertz half-width a >= R.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/finiteness.h>
#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/core/parameter_error.h>

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
  // Whether @p j holds a null anywhere (nlohmann writes NaN as null).
  bool
  has_null(const nlohmann::json &j)
  {
    if (j.is_null())
      return true;
    if (j.is_structured())
      for (const auto &item : j)
        if (has_null(item))
          return true;
    return false;
  }

  struct Result
  {
    double      epsilon = -1;
    std::string error;
    bool        summary_has_null = false;
    /** epsilon_E^2 = e_E^2 / D^2 of the last cycle's locally owned cells,
     * both bodies. */
    std::vector<double> element_epsilon_squared;
    /** Per cycle: DoFs, active, stick and slip nodes. */
    std::vector<std::array<unsigned int, 4>> cycles;
    /** The last cycle's contact force (y, N/mm) as reported. */
    double         contact_force = 0;
    nlohmann::json summary;
    std::string    log;
  };

  Result
  run(const std::vector<std::pair<std::string, std::string>> &settings,
      const std::string                                      &directory)
  {
    ParameterHandler prm;
    // The settings below first: @p settings may override them.
    testing::Settings all;
    // The direct solver: the solutions of scaled problems agree to
    // round-off (1e-12 below). A Krylov solve (Type = auto takes it above
    // 5,000 DoFs, the second cycle here) stops at a relative residual of
    // 1e-12, which a factor that is no power of 2 (moduli times 1e-100)
    // does not reproduce to that accuracy in every element's epsilon_E.
    all.insert(all.end(),
               {{"Linear solver/Type", "direct"},
                {"Adaptation/Strategy", "refine"},
                {"Adaptation/Target error", "1"},
                {"Adaptation/Number of cycles", "2"},
                {"Output/Write VTU", "false"},
                {"Output/Output directory", directory}});
    all.insert(all.end(), settings.begin(), settings.end());
    const Parameters parameters = testing::make_parameters(prm, all);
    prepare_output_directory(parameters.output.directory, MPI_COMM_WORLD);
    std::ostringstream log;
    Result             result;
    try
      {
        TwoBodyProblem problem(MPI_COMM_WORLD, parameters, prm, "test", log);
        problem.run();
        const ErrorEstimate &e = problem.last_error_estimate();
        result.epsilon         = e.epsilon;
        for (unsigned int b = 0; b < 2; ++b)
          for (const auto &cell :
               problem.body(b).triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              result.element_epsilon_squared.push_back(
                e.contribution_squared[b][cell->active_cell_index()] /
                e.normalisation_squared);
      }
    catch (const NonFiniteResult &e)
      {
        result.error = e.what();
      }
    catch (const ParameterError &e)
      {
        result.error = e.what();
      }
    result.log = log.str();
    MPI_Barrier(MPI_COMM_WORLD);
    std::ifstream summary(parameters.output.directory + "/summary.json");
    if (summary)
      {
        summary >> result.summary;
        result.summary_has_null = has_null(result.summary);
        for (const auto &c : result.summary["cycles"])
          {
            result.cycles.push_back({{c["n_dofs"].get<unsigned int>(),
                                      c.value("active_nodes", 0u),
                                      c.value("stick_nodes", 0u),
                                      c.value("slip_nodes", 0u)}});
            if (c.contains("contact_force"))
              result.contact_force = c["contact_force"][1].get<double>();
          }
      }
    return result;
  }

  Result
  run_blocks(const std::string &pressure)
  {
    return run({{"Scene/Name", "blocks"}, {"Scene/Blocks/Pressure", pressure}},
               "output-" + pressure);
  }

  // Whether @p r has the epsilon, every epsilon_E and the DoFs and contact
  // sets of every cycle of @p reference, to @p tolerance, on every rank.
  bool
  same_solution(const Result &r,
                const Result &reference,
                const double  tolerance)
  {
    bool same =
      r.error.empty() && r.cycles == reference.cycles &&
      r.element_epsilon_squared.size() ==
        reference.element_epsilon_squared.size() &&
      std::abs(r.epsilon - reference.epsilon) <= tolerance * reference.epsilon;
    if (same)
      {
        double largest = 0;
        for (const double x : reference.element_epsilon_squared)
          largest = std::max(largest, x);
        for (unsigned int i = 0; i < r.element_epsilon_squared.size(); ++i)
          same = same && std::abs(r.element_epsilon_squared[i] -
                                  reference.element_epsilon_squared[i]) <=
                           tolerance * largest;
      }
    return Utilities::MPI::min(same ? 1u : 0u, MPI_COMM_WORLD) == 1;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const Result reference = run_blocks("1");
  out << "pressure 1: epsilon = " << std::fixed << std::setprecision(6)
      << 100 * reference.epsilon << " %" << std::defaultfloat << std::endl;
  AssertThrow(reference.epsilon > 0.01 && reference.error.empty(),
              ExcMessage("the reference run failed"));
  AssertThrow(!reference.summary_has_null, ExcMessage("null in summary"));
  AssertThrow(!reference.summary.contains("load_scale"),
              ExcMessage("ordinary loads scaled"));

  for (const std::string pressure : {"1e-110", "1e110"})
    {
      const Result r = run_blocks(pressure);
      const double difference =
        std::abs(r.epsilon - reference.epsilon) / reference.epsilon;
      out << "pressure " << pressure << ": epsilon = " << std::fixed
          << std::setprecision(6) << 100 * r.epsilon << " %"
          << std::defaultfloat << ", same as pressure 1 to 1e-12: "
          << (difference <= 1e-12 ? "yes" : "no")
          << ", summary.json without null: "
          << (r.summary_has_null ? "no" : "yes") << std::endl;
      AssertThrow(r.error.empty(), ExcMessage(r.error));
      AssertThrow(difference <= 1e-12, ExcMessage("not homogeneous"));
      AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
    }

  // Beyond the comfortable range (as are 1e-110 and 1e110 above): scaled
  // by a power of 2.
  for (const std::string pressure :
       {"1e-300", "1e-200", "1e-130", "1e130", "1e200", "1e300"})
    {
      const Result r     = run_blocks(pressure);
      const bool   same  = same_solution(r, reference, 1e-12);
      const double scale = r.summary.value("load_scale", 0.);
      // The reported force is the physical one: pressure times that of
      // pressure 1.
      const double force_ratio =
        r.contact_force / std::stod(pressure) / reference.contact_force;
      const bool same_force      = std::abs(force_ratio - 1) <= 1e-12;
      const bool energies_scaled = r.summary.contains("reported_scaled") &&
                                   r.summary["reported_scaled"].dump().find(
                                     "strain_energy") != std::string::npos;
      out << "pressure " << pressure << ": load scale 2^"
          << (scale > 0 ? std::ilogb(scale) : 0) << ", epsilon = " << std::fixed
          << std::setprecision(6) << 100 * r.epsilon << " %"
          << std::defaultfloat
          << ", epsilon, epsilon_E, DoFs and contact sets of each cycle as "
             "pressure 1 to 1e-12: "
          << (same ? "yes" : "no")
          << ", contact force / pressure as pressure 1 to 1e-12: "
          << (same_force ? "yes" : "no")
          << ", energies reported scaled: " << (energies_scaled ? "yes" : "no")
          << ", summary.json without null: "
          << (r.summary_has_null ? "no" : "yes") << std::endl;
      AssertThrow(r.error.empty(), ExcMessage(r.error));
      AssertThrow(same && same_force, ExcMessage("not homogeneous"));
      AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
      AssertThrow(r.log.empty() ||
                    r.log.find("solved with the loads divided by the load "
                               "scale") != std::string::npos,
                  ExcMessage("the log does not say the loads were scaled"));
    }

  // Moduli times 1e+-100 with the loads alike: the same strains.
  for (const std::string factor : {"1e-100", "1e100"})
    {
      std::ostringstream E;
      E << 130000. * std::stod(factor);
      const Result r     = run({{"Scene/Name", "blocks"},
                                {"Scene/Blocks/Pressure", factor},
                                {"Scene/Blocks/Body 1/Young's modulus", E.str()},
                                {"Scene/Blocks/Body 2/Young's modulus", E.str()}},
                           "output-moduli-" + factor);
      const bool   same  = same_solution(r, reference, 1e-12);
      const double scale = r.summary.value("load_scale", 1.);
      out << "moduli and pressure times " << factor << ": load scale 2^"
          << std::ilogb(scale) << ", epsilon = " << std::fixed
          << std::setprecision(6) << 100 * r.epsilon << " %"
          << std::defaultfloat
          << ", epsilon, epsilon_E, DoFs and contact sets of each cycle as "
             "pressure 1 to 1e-12: "
          << (same ? "yes" : "no") << ", summary.json without null: "
          << (r.summary_has_null ? "no" : "yes") << std::endl;
      AssertThrow(r.error.empty(), ExcMessage(r.error));
      AssertThrow(same, ExcMessage("moduli: not the same solution"));
      AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
    }

  // Moduli and loads both beyond 1e+-100 (before: moduli and pressure
  // times 1e200 "would slide"): divided together by a power of 2, the
  // strains stay (displacement scale 1): the same epsilon, every epsilon_E,
  // DoFs and contact sets; the force and the strain energy scale with the
  // factor. Then moduli alone beyond 1e+-100 (strains of 1e-253 ... 1e148
  // with ordinary loads; before: a stop after the solve for the smallest
  // moduli): the displacements are scaled too; the same solution, the
  // same force, the energy divided by the factor.
  const auto strain_energy = [](const Result &x) {
    return x.summary["cycles"]
      .back()["bodies"][0]["strain_energy"]
      .get<double>();
  };
  const auto scale_exponent = [](const Result &x, const char *key) {
    return x.summary.contains(key) ? std::ilogb(x.summary[key].get<double>()) :
                                     0;
  };
  for (const bool with_loads : {true, false})
    for (const std::string &factor :
         with_loads ?
           std::vector<std::string>{"1e-300", "1e-200", "1e200", "1e300"} :
           std::vector<std::string>{"1e-150", "1e-250", "1e150", "1e250"})
      {
        std::ostringstream E;
        E << std::setprecision(17) << 130000. * std::stod(factor);
        const std::string pressure = with_loads ? factor : "1";
        const Result      r =
          run({{"Scene/Name", "blocks"},
               {"Scene/Blocks/Pressure", pressure},
               {"Scene/Blocks/Body 1/Young's modulus", E.str()},
               {"Scene/Blocks/Body 2/Young's modulus", E.str()}},
              "output-moduli-" + factor + (with_loads ? "-loads" : ""));
        const bool   same     = same_solution(r, reference, 1e-12);
        const double f        = std::stod(factor);
        const bool same_force = std::abs(r.contact_force / std::stod(pressure) /
                                           reference.contact_force -
                                         1) <= 1e-12;
        const double energy_ratio = strain_energy(r) /
                                    strain_energy(reference) /
                                    (with_loads ? f : 1 / f);
        const bool same_energy = std::abs(energy_ratio - 1) <= 1e-12;
        out << (with_loads ? "moduli and pressure" : "moduli") << " times "
            << factor << ": load scale 2^" << scale_exponent(r, "load_scale")
            << ", displacement scale 2^"
            << (r.summary.contains("displacement_scale") ?
                  scale_exponent(r, "displacement_scale") :
                  scale_exponent(r, "load_scale"))
            << ", epsilon = " << std::fixed << std::setprecision(6)
            << 100 * r.epsilon << " %" << std::defaultfloat
            << ", epsilon, epsilon_E, DoFs and contact sets of each cycle as "
               "pressure 1 to 1e-12: "
            << (same ? "yes" : "no") << ", contact force / pressure as "
            << "pressure 1 to 1e-12: " << (same_force ? "yes" : "no")
            << ", strain energy times " << (with_loads ? "factor" : "1/factor")
            << " to 1e-12: " << (same_energy ? "yes" : "no")
            << ", summary.json without null: "
            << (r.summary_has_null ? "no" : "yes") << std::endl;
        AssertThrow(r.error.empty(), ExcMessage(r.error));
        AssertThrow(same && same_force && same_energy,
                    ExcMessage("moduli: not the same solution"));
        AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
      }

  // Strains that no double holds (moduli 1e-200, pressure 1e200: 1e400):
  // no scaling helps; a stop before the solve on every rank, naming the
  // entries and the range.
  {
    const Result       r = run({{"Scene/Name", "blocks"},
                                {"Scene/Blocks/Pressure", "1e200"},
                                {"Scene/Blocks/Body 1/Young's modulus", "1e-200"},
                                {"Scene/Blocks/Body 2/Young's modulus", "1e-200"}},
                         "output-moduli-strain-overflow");
    const unsigned int n_stopped =
      Utilities::MPI::sum(r.error.empty() ? 0u : 1u, MPI_COMM_WORLD);
    const bool names_it =
      r.error.find("scene 'blocks', 'Scene/Blocks/Pressure', "
                   "'Scene/Blocks/Body 1/Young's modulus', "
                   "'Scene/Blocks/Body 2/Young's modulus'") !=
        std::string::npos &&
      r.error.find("strains of the order of 10^400") != std::string::npos &&
      r.error.find("outside 1e-300 ... 1e300") != std::string::npos;
    const bool before_solving =
      r.log.find("Newton") == std::string::npos && r.cycles.empty();
    out << "moduli 1e-200, pressure 1e200: stopped on " << n_stopped << "/"
        << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
        << " ranks before solving: " << (before_solving ? "yes" : "no")
        << ", message names the entries, the strain and the range: "
        << (names_it ? "yes" : "no") << std::endl;
    AssertThrow(n_stopped == Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
                ExcMessage("not stopped on every rank"));
    AssertThrow(names_it && before_solving, ExcMessage("message: " + r.error));
  }

  // Without contact: the manufactured solution's body force, tractions
  // and exact displacement scale together (before: amplitude 1e200 gave
  // epsilon = nan and a CSV of -nan).
  const auto run_manufactured = [&](const std::string &amplitude) {
    return run({{"Scene/Name", "manufactured"},
                {"Scene/Manufactured/Amplitude", amplitude}},
               "output-manufactured-" + amplitude);
  };
  const Result manufactured = run_manufactured("1");
  out << "manufactured, amplitude 1: epsilon = " << std::fixed
      << std::setprecision(6) << 100 * manufactured.epsilon << " %"
      << std::defaultfloat << std::endl;
  AssertThrow(manufactured.error.empty(), ExcMessage(manufactured.error));
  for (const std::string amplitude : {"1e-300", "1e200"})
    {
      const Result r     = run_manufactured(amplitude);
      const bool   same  = same_solution(r, manufactured, 1e-12);
      const double scale = r.summary.value("load_scale", 1.);
      // The exact error relative to the exact solution's energy norm.
      const auto relative_exact_error = [](const Result &x) {
        return x.summary["cycles"]
          .back()["bodies"][0]["exact_error"]["relative_energy"]
          .get<double>();
      };
      const bool same_exact_error =
        std::abs(relative_exact_error(r) / relative_exact_error(manufactured) -
                 1) <= 1e-12;
      out << "manufactured, amplitude " << amplitude << ": load scale 2^"
          << std::ilogb(scale) << ", epsilon = " << std::fixed
          << std::setprecision(6) << 100 * r.epsilon << " %"
          << std::defaultfloat
          << ", epsilon, epsilon_E and DoFs of each cycle as amplitude 1 to "
             "1e-12: "
          << (same ? "yes" : "no")
          << ", relative exact error as amplitude 1 to 1e-12: "
          << (same_exact_error ? "yes" : "no")
          << ", summary.json without null: "
          << (r.summary_has_null ? "no" : "yes") << std::endl;
      AssertThrow(r.error.empty(), ExcMessage(r.error));
      AssertThrow(same && same_exact_error, ExcMessage("not homogeneous"));
      AssertThrow(!r.summary_has_null, ExcMessage("null in summary"));
    }

  // Hertz's curved surfaces have an initial gap, which does not scale
  // with the loads alone; with the moduli divided alike the strains, and
  // so the gap, stay: line load and moduli times 2^133 = 1.1e40 (stresses
  // beyond the 32-bit floats of the field files) are solved with both divided
  // by a power of 2, displacements as given, and give the epsilon, every
  // epsilon_E, the DoFs and the contact sets of factor 1 to 1e-12 (before:
  // solved as given, inf in the field files).
  {
    // A power of 2, so that the loads and moduli given are exactly those
    // of factor 1 times it (a decimal factor rounds them differently,
    // which moved epsilon by 3e-12).
    const auto run_hertz = [&](const int exponent) {
      std::ostringstream load, E;
      load << std::setprecision(17) << std::ldexp(1000., exponent);
      E << std::setprecision(17) << std::ldexp(130000., exponent);
      return run({{"Scene/Name", "hertz"},
                  {"Scene/Hertz/Line load", load.str()},
                  {"Scene/Hertz/Body 1/Young's modulus", E.str()},
                  {"Scene/Hertz/Body 2/Young's modulus", E.str()},
                  {"Scene/Hertz/Contact mesh size", "1"},
                  {"Adaptation/Number of cycles", "1"},
                  {"Adaptation/Minimum number of cycles", "1"}},
                 "output-hertz-moduli-" + std::to_string(exponent));
    };
    const Result hertz = run_hertz(0);
    const Result r     = run_hertz(133);
    const bool   same  = same_solution(r, hertz, 1e-12);
    out << "hertz, line load and moduli times 2^133 = 1.1e40: load scale 2^"
        << scale_exponent(r, "load_scale") << ", displacement scale 2^"
        << scale_exponent(r, "displacement_scale")
        << ", epsilon = " << std::fixed << std::setprecision(6)
        << 100 * r.epsilon << " %" << std::defaultfloat
        << ", epsilon, epsilon_E, DoFs and contact sets of each cycle as "
           "factor 1 to 1e-12: "
        << (same ? "yes" : "no") << std::endl;
    AssertThrow(hertz.error.empty() && r.error.empty(),
                ExcMessage(hertz.error + r.error));
    AssertThrow(same && scale_exponent(r, "load_scale") != 0 &&
                  scale_exponent(r, "displacement_scale") == 0,
                ExcMessage("hertz: not scaled, or not the same solution"));
  }

  // Not homogeneous in the loads alone, and strains beyond any scaling
  // that keeps the gap.
  for (const std::string load : {"1e-200", "1e200"})
    {
      const Result       r = run({{"Scene/Name", "hertz"},
                                  {"Scene/Hertz/Line load", load},
                                  {"Scene/Hertz/Contact mesh size", "0"},
                                  {"Scene/Hertz/Hold axis", "false"},
                                  {"Mesh/Global refinements", "2"}},
                           "output-hertz-" + load);
      const unsigned int n_stopped =
        Utilities::MPI::sum(r.error.empty() ? 0u : 1u, MPI_COMM_WORLD);
      // 1e200 N/mm is refused first for its Hertz half-width (4e98 mm
      // against R = 100 mm), when the scene reads its parameters.
      const bool names_it =
        load == "1e200" ?
          r.error.find("'Scene/Hertz/Line load' has the value '1e+200'") !=
              std::string::npos &&
            r.error.find("not small against the radius") != std::string::npos :
          r.error.find("scene 'hertz', 'Scene/Hertz/Line load'") !=
              std::string::npos &&
            r.error.find("initial gap") != std::string::npos &&
            r.error.find("not linear in the loads") != std::string::npos;
      // Nothing solved: the log has no contact solve, no cycle recorded.
      const bool before_solving =
        r.log.find("Newton") == std::string::npos && r.cycles.empty();
      out << "hertz, line load " << load << ": stopped on " << n_stopped << "/"
          << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
          << " ranks before solving: " << (before_solving ? "yes" : "no")
          << ", message names the entry and the "
          << (load == "1e200" ? "half-width" : "gap") << ": "
          << (names_it ? "yes" : "no") << std::endl;
      AssertThrow(n_stopped == Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
                  ExcMessage("not stopped on every rank"));
      AssertThrow(names_it && before_solving,
                  ExcMessage("message: " + r.error));
    }
}
