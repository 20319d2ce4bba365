// Lame's contact pressure of the press fit in prm/meshes/press_fit*.geo,
// shared by the press-fit tests.
#ifndef coulomb_adapt_tests_lame_press_fit_h
#define coulomb_adapt_tests_lame_press_fit_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace coulomb_adapt
{
  namespace testing
  {
    /** The press fit's geometry and material (prm/press_fit*.prm). */
    struct PressFit
    {
      double E = 200000, nu = 0.3, b = 10, c = 20, delta = 0.001;

      /** theory.md section 9, with the hub's bore a = b (the formula's
       * small-interference limit). */
      double
      pressure_for_equal_radii() const
      {
        return E * delta * (c * c - b * b) / (2 * b * c * c * (1 - nu * nu));
      }

      /** The plane-strain Lame pressure for the actual radii: a shaft of
       * radius b in a hub of bore a = b - delta and outer radius c, the
       * radial displacements of both meeting at the interface. */
      double
      pressure() const
      {
        const double a = b - delta;
        return E * delta /
               ((1 + nu) *
                (a * ((1 - 2 * nu) * a * a + c * c) / (c * c - a * a) +
                 (1 - 2 * nu) * b));
      }
    };

    /** The press fit of prm/press_fit_torque.prm: a hollow shaft (bore
     * radius a0, outer radius b) in a hub of bore a = b - delta and outer
     * radius c, the shaft's bore and the hub's outer circle held radially
     * (u_r = 0 there), plane strain. The radial (Lame) and the tangential
     * (torsion) problems of the annuli are uncoupled. */
    struct HeldPressFit
    {
      double E = 200000, nu = 0.3, a0 = 5, b = 10, c = 20, delta = 0.001;

      double
      shear_modulus() const
      {
        return E / (2 * (1 + nu));
      }

      /** u = A r + B / r in each annulus, B = -A r_held^2 at its held
       * radius, sigma_r = 2 (lambda + G) A - 2 G B / r^2 = -p at the
       * interface; the radial displacements meet: u_shaft(b) - u_hub(a) =
       * a - b = -delta. */
      double
      pressure() const
      {
        const double a      = b - delta;
        const double G      = shear_modulus();
        const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
        // u at the interface per unit pressure, for an annulus held at
        // r_held and loaded at r.
        const auto compliance = [&](const double r, const double r_held) {
          return -(r - r_held * r_held / r) /
                 (2 * (lambda + G) + 2 * G * r_held * r_held / (r * r));
        };
        return delta / (compliance(a, c) - compliance(b, a0));
      }

      /** The torque (per unit thickness) that the interface transmits when
       * all of it slips: mu p times the bore's length 2 pi a times the
       * lever arm a (the slave side, the hub's bore, carries the
       * tractions). */
      double
      full_slip_torque(const double mu) const
      {
        const double a = b - delta;
        return mu * pressure() * 2 * dealii::numbers::PI * a * a;
      }

      /** The torque while the whole interface sticks at a rotation theta
       * of the shaft's bore: u_theta = r phi(r) with
       * phi' = T / (2 pi G r^3) in each annulus, phi = 0 at c, phi = theta
       * at a0, and u_theta of the hub at a equal to the shaft's at b (the
       * mortar's normal projection). */
      double
      stick_torque(const double theta) const
      {
        const double a = b - delta;
        return 4 * dealii::numbers::PI * shear_modulus() * b * theta /
               (a * (1 / (a * a) - 1 / (c * c)) +
                b * (1 / (a0 * a0) - 1 / (b * b)));
      }
    };

    /** The slave nodes' pressures of one cycle against Lame's p. */
    struct SlavePressures
    {
      unsigned int n_nodes = 0;
      /** max |p_j - p| / p over the slave nodes. */
      double largest_deviation = 0;
      /** sum w_j p_j / sum w_j (w_j the mortar weights). */
      double mean = 0;
    };

    /** Read cycle @p cycle's contact CSV in @p directory (x, y, normal_x,
     * normal_y, weight, contact_pressure, ...). */
    inline SlavePressures
    read_slave_pressures(const std::string &directory,
                         const unsigned int cycle,
                         const double       p)
    {
      std::ifstream file(directory + "/contact_" +
                         dealii::Utilities::int_to_string(cycle, 3) + ".csv");
      std::string   line;
      std::getline(file, line);
      SlavePressures result;
      double         force = 0, length = 0;
      while (std::getline(file, line))
        {
          std::istringstream row(line);
          std::string        field;
          double             weight = 0;
          for (unsigned int k = 0; k < 6; ++k)
            {
              std::getline(row, field, ',');
              if (k == 4)
                weight = std::stod(field);
            }
          const double pressure = std::stod(field);
          result.largest_deviation =
            std::max(result.largest_deviation, std::abs(pressure - p) / p);
          force += pressure * weight;
          length += weight;
          ++result.n_nodes;
        }
      result.mean = length > 0 ? force / length : 0;
      return result;
    }
  } // namespace testing
} // namespace coulomb_adapt

#endif
