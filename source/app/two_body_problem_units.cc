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
  // the loads: such a problem is solved as given while its stresses keep
  // the indicator's squares in the range of doubles, and refused before
  // the solve beyond.
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
    for (const auto &body : bodies)
      {
        const double E = body->description().material.youngs_modulus;
        if (E > units::comfortable_modulus ||
            E < 1 / units::comfortable_modulus)
          return choose_scales_for_moduli(loads, s, source);
      }
    const double load_scale = units::load_scale_for(loads.stress);
    if (load_scale == 1)
      {
        pcout << s.str() << ": solved as given (load scale 1)" << std::endl;
        return;
      }
    const double gap = has_contact() ? largest_initial_gap(bodies) : 0.;
    if (gap > 1e-12 * loads.size)
      {
        s << ", and the contact curves have an initial gap or overlap of up "
             "to "
          << gap
          << " mm: the problem is not linear in the loads (theory.md "
             "section 6, Homogeneity), so they cannot be scaled";
        if (loads.stress <= units::accepted_stress &&
            loads.stress >= 1 / units::accepted_stress)
          {
            pcout << s.str() << "; solved as given (load scale 1)" << std::endl;
            return;
          }
        throw ParameterError(
          source + s.str().substr(9) +
          ". With an initial gap the loads must keep stresses within "
          "1e-120 ... 1e120 MPa in the units of the moduli (e.g. N, mm, "
          "MPa): beyond, the error indicator's squares of stresses leave "
          "the range of doubles. Without a gap (touching contact curves) "
          "any load in the range of doubles is solved");
      }
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



  // Moduli beyond 1e+-100 MPa: stresses and moduli are divided by P
  // alike, so that the strains stay those of the problem (D = 1: exact
  // also with an initial gap); strains beyond 1e+-100 are brought to
  // moderate ones by a displacement scale D (then the problem must be
  // homogeneous: no initial gap). Strains beyond 1e+-300 are no
  // displacements a double holds once multiplied by the bodies' size.
  void
  TwoBodyProblem::choose_scales_for_moduli(const LoadStressScale &loads,
                                           std::ostringstream    &s,
                                           const std::string     &source)
  {
    const double E1 = bodies[0]->description().material.youngs_modulus;
    const double E2 = bodies[1]->description().material.youngs_modulus;
    // The geometric mean, without overflow.
    const double modulus = std::sqrt(E1) * std::sqrt(E2);
    s << ", Young's moduli " << E1 << " and " << E2
      << " MPa (outside 1e-100 ... 1e100 MPa)";
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
        std::to_string(static_cast<long>(std::lround(
          std::log10(std::max(loads.stress, 1e-300)) - std::log10(modulus)))) +
        " (stress scale over modulus), outside 1e-300 ... 1e300: the "
        "displacements would be no doubles, and no scaling of loads and "
        "moduli changes the strains. Give loads and moduli whose ratio is "
        "a strain within 1e-300 ... 1e300 (e.g. N, mm, MPa)");
    const double gap = has_contact() ? largest_initial_gap(bodies) : 0.;
    if (scales.displacement != 1 && gap > 1e-12 * loads.size)
      throw ParameterError(
        source.substr(0, source.size() - 2) + ", " + moduli_entries + ": " +
        s.str().substr(9) +
        ": strains beyond 1e-100 ... 1e100 need the "
        "displacements scaled, but the contact curves have an initial gap "
        "or overlap of up to " +
        std::to_string(gap) +
        " mm: the problem is not linear in the loads (theory.md section 6, "
        "Homogeneity). Give loads and moduli whose ratio is a strain "
        "within 1e-100 ... 1e100");
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
    pcout << s.str() << std::endl;
    // The bodies hold their moduli: made again from the scaled scene.
    make_bodies();
    setup_system();
  }
} // namespace coulomb_adapt
