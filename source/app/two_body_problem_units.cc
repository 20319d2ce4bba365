#include <coulomb_adapt/app/load_scaling.h>
#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/core/units.h>

#include <cmath>
#include <iomanip>
#include <sstream>

// The units of a run (theory.md section 6, Homogeneity): the scales by
// which loads, moduli and displacements are divided, chosen on the first
// meshes, or a stop before the solve where no scaling applies.
namespace coulomb_adapt
{
  // Theory.md section 6: with zero initial gap the static problem is
  // positively homogeneous in the loads (tractions, body forces and
  // prescribed displacements together), so the loads divided by a power
  // of 2 give the same contact sets, epsilon, epsilon_E and meshes, and
  // the displacements, stresses and forces divided by it. A gap (Hertz's
  // curved surfaces, a clearance, an interference) does not scale with
  // the loads alone, but with the loads and moduli divided together the
  // strains, and so the gaps, stay exactly as they are. Problems whose
  // scales are comfortable (units.h: stresses, displacements and energy
  // densities that 32-bit floats hold in the field files) are solved as
  // given.
  void
  TwoBodyProblem::choose_load_scale(const LoadStressScale &loads)
  {
    std::ostringstream s;
    s << std::setprecision(3) << "  units: the loads' stress scale is "
      << loads.stress << " MPa";
    if (!loads.where.empty())
      s << " (" << loads.where << ")";
    // Messages name the scene's load entries (and the mesh file).
    std::string entries;
    for (const std::string &entry : scene->load_entries())
      entries += (entries.empty() ? "'" : ", '") + entry + "'";
    const std::string source =
      mesh_source + "scene '" + scene->name() + "', " + entries + ": ";
    if (!std::isfinite(loads.stress))
      throw ParameterError(
        source + s.str().substr(9) +
        ": not a finite number. Give loads and moduli in units that keep "
        "stresses finite (e.g. N, mm, MPa)");
    const double E1 = bodies[0]->description().material.youngs_modulus;
    const double E2 = bodies[1]->description().material.youngs_modulus;
    if (units::solvable_as_given(loads.stress, E1, E2))
      {
        pcout << s.str() << ": solved as given (load scale 1)" << std::endl;
        return;
      }
    // Loads alone divided by P (and so displacements, D = P) leave a
    // problem of moderate stresses, strains and energies if the moduli
    // are comfortable; but gaps do not scale with the loads. Else the
    // moduli are divided with the loads (displacements stay, so gaps too)
    // and, if the strains are extreme, the displacements.
    const bool gap =
      has_contact() && largest_initial_gap(bodies) > 1e-12 * loads.size;
    if (gap || !units::is_comfortable(E1) || !units::is_comfortable(E2))
      return choose_scales_for_moduli(loads, s, source);
    const double load_scale = units::power_of_two_near(loads.stress);
    scene->set_load_scale(load_scale);
    cycle_report->set_load_scale(load_scale);
    pcout << s.str() << ": solved with the loads divided by the load scale "
          << "2^" << std::ilogb(load_scale) << " = " << load_scale
          << " (theory.md section 6, Homogeneity); displacements, stresses "
             "and forces are reported multiplied by it, energies by its "
             "square"
          << std::endl;
    // The constraints hold the prescribed displacements.
    setup_system();
  }



  // Stresses and moduli are divided by P alike, so that the strains stay
  // those of the problem (D = 1: exact also with an initial gap); strains
  // beyond the comfortable range are brought to moderate ones by a
  // displacement scale D (then the problem must be homogeneous: no initial
  // gap). Strains beyond 1e+-300 are no displacements a double holds once
  // multiplied by the bodies' size.
  void
  TwoBodyProblem::choose_scales_for_moduli(const LoadStressScale &loads,
                                           std::ostringstream    &s,
                                           const std::string     &source)
  {
    const double E1 = bodies[0]->description().material.youngs_modulus;
    const double E2 = bodies[1]->description().material.youngs_modulus;
    // The geometric mean, without overflow.
    const double modulus = std::sqrt(E1) * std::sqrt(E2);
    const double gap     = has_contact() ? largest_initial_gap(bodies) : 0.;
    const long   strain_exponent = std::lround(
      std::log10(std::max(loads.stress, 1e-300)) - std::log10(modulus));
    s << ", Young's moduli " << E1 << " and " << E2 << " MPa";
    if (!units::is_comfortable(E1) || !units::is_comfortable(E2))
      s << " (outside " << units::comfortable_range() << " MPa)";
    // The messages name the moduli's entries beside the loads'.
    const std::string scene_path =
      scene->load_entries().empty() ?
        std::string() :
        scene->load_entries()[0].substr(0,
                                        scene->load_entries()[0].find('/', 6) +
                                          1);
    const std::string moduli_entries = "'" + scene_path +
                                       "Body 1/Young's modulus', '" +
                                       scene_path + "Body 2/Young's modulus'";
    units::Scales scales;
    if (!units::scales_for_moduli(loads.stress, modulus, scales))
      throw ParameterError(
        source.substr(0, source.size() - 2) + ", " + moduli_entries + ": " +
        s.str().substr(9) + ": strains of the order of 10^" +
        std::to_string(strain_exponent) +
        " (stress scale over modulus), outside 1e-300 ... 1e300: the "
        "displacements would be no doubles, and no scaling of loads and "
        "moduli changes the strains. Give loads and moduli whose ratio is "
        "a strain within 1e-300 ... 1e300 (e.g. N, mm, MPa)");
    if (scales.displacement != 1 && gap > 1e-12 * loads.size)
      throw ParameterError(
        source.substr(0, source.size() - 2) + ", " + moduli_entries + ": " +
        s.str().substr(9) + ": strains of the order of 10^" +
        std::to_string(strain_exponent) +
        " (stress scale over modulus), beyond " + units::comfortable_range() +
        ", need the displacements scaled, but the contact curves have an "
        "initial gap or overlap of up to " +
        std::to_string(gap) +
        " mm: the problem is not linear in the loads (theory.md section 6, "
        "Homogeneity). Give loads and moduli whose ratio is a strain "
        "within " +
        units::comfortable_range() +
        " (e.g. N, mm, MPa). Without a gap (touching contact curves) any "
        "load in the range of doubles is solved");
    scene->set_scales(scales);
    cycle_report->set_scales(scales);
    s << ": solved with the loads divided by the load scale 2^"
      << std::ilogb(scales.stress) << " = " << scales.stress
      << ", the moduli by 2^" << std::ilogb(scales.modulus()) << " = "
      << scales.modulus() << " and displacements by 2^"
      << std::ilogb(scales.displacement) << " = " << scales.displacement
      << " (theory.md section 6, Homogeneity); stresses and forces are "
         "reported multiplied by the load scale, displacements by the "
         "displacement scale, energies by both";
    if (gap > 1e-12 * loads.size)
      s << "; with the initial gap or overlap of up to " << gap
        << " mm, which does not scale with the loads alone";
    pcout << s.str() << std::endl;
    // The bodies hold their moduli: made again from the scaled scene.
    make_bodies();
    setup_system();
  }
} // namespace coulomb_adapt
