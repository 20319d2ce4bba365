#include <coulomb_adapt/core/units.h>

#include <cmath>
#include <limits>
#include <string>

namespace coulomb_adapt
{
  namespace units
  {
    double
    power_of_two_near(const double magnitude)
    {
      return std::ldexp(1.,
                        static_cast<int>(std::lround(std::log2(magnitude))));
    }



    bool
    is_comfortable(const double magnitude)
    {
      return magnitude == 0 || (magnitude <= comfortable_scale &&
                                magnitude >= 1 / comfortable_scale);
    }



    std::string
    comfortable_range()
    {
      const std::string exponent =
        std::to_string(std::lround(std::log10(comfortable_scale)));
      return "1e-" + exponent + " ... 1e" + exponent;
    }



    namespace
    {
      // Base-2 logarithms: the strain and the energy density of extreme
      // loads and moduli may be no doubles at all.
      double
      log2_strain(const double stress_scale, const double E1, const double E2)
      {
        return std::log2(stress_scale) - 0.5 * (std::log2(E1) + std::log2(E2));
      }



      // The strain scale, the stress over the moduli's geometric mean, is 0
      // or comfortable.
      bool
      strain_is_comfortable(const double stress_scale,
                            const double E1,
                            const double E2)
      {
        return stress_scale == 0 ||
               std::abs(log2_strain(stress_scale, E1, E2)) <=
                 std::log2(comfortable_scale);
      }
    } // namespace



    bool
    solvable_as_given(const double stress_scale,
                      const double E1,
                      const double E2)
    {
      if (!is_comfortable(E1) || !is_comfortable(E2) ||
          !is_comfortable(stress_scale) ||
          !strain_is_comfortable(stress_scale, E1, E2))
        return false;
      return stress_scale == 0 || std::abs(std::log2(stress_scale) +
                                           log2_strain(stress_scale, E1, E2)) <=
                                    std::log2(comfortable_scale);
    }



    // A quantity of one sign is all physical or all scaled, whatever its
    // values: energies (power 2) are scaled where P^2 is no normal double,
    // others where the product overflows. A product that underflows is the
    // physical value rounded to the doubles (0 or subnormal): round-off
    // noise such as a horizontal force of 1e-14 of the scaled problem.
    // One factor P at a time: P^2 alone may overflow where the product
    // does not.
    bool
    to_physical(const double scaled_value,
                const double load_scale,
                const int    power,
                double      &physical)
    {
      const double factor = std::pow(load_scale, power);
      if (power > 1 && !std::isnormal(factor))
        return false;
      double value = scaled_value;
      for (int i = 0; i < power; ++i)
        value *= load_scale;
      if (!std::isfinite(value))
        return false;
      physical = value;
      return true;
    }



    bool
    scales_for_moduli(const double stress_scale,
                      const double modulus,
                      Scales      &scales)
    {
      // In base-2 logarithms: the strain may be no double at all.
      const double log2_modulus = std::log2(modulus);
      const double log2_stress =
        stress_scale > 0 ? std::log2(stress_scale) : log2_modulus;
      const double log2_strain = log2_stress - log2_modulus;
      if (std::abs(log2_strain) > std::log2(largest_strain))
        return false;
      scales.stress =
        std::ldexp(1., static_cast<int>(std::lround(log2_stress)));
      scales.displacement =
        std::abs(log2_strain) <= std::log2(comfortable_scale) ?
          1. :
          std::ldexp(1., static_cast<int>(std::lround(log2_strain)));
      return true;
    }



    // One factor at a time (P, then D): the product may be a double where
    // P D is not.
    bool
    to_physical(const double  scaled_value,
                const Scales &scales,
                const Kind    kind,
                double       &physical)
    {
      const double P = scales.stress, D = scales.displacement;
      double       value = scaled_value;
      switch (kind)
        {
          case Kind::stress:
            value *= P;
            break;
          case Kind::displacement:
            value *= D;
            break;
          case Kind::energy:
            if (!std::isnormal(std::ldexp(1., std::ilogb(P) + std::ilogb(D))))
              return false;
            value = value * P * D;
            break;
          case Kind::energy_norm:
            // With D = P exactly P (the loads scaled alone).
            value = P == D ? value * P : value * std::sqrt(P) * std::sqrt(D);
            break;
        }
      if (!std::isfinite(value))
        return false;
      physical = value;
      return true;
    }
  } // namespace units
} // namespace coulomb_adapt
