#include <coulomb_adapt/core/units.h>

#include <cmath>
#include <limits>

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



    double
    load_scale_for(const double stress_scale)
    {
      if (!(stress_scale > 0) || !std::isfinite(stress_scale) ||
          (stress_scale <= comfortable_stress &&
           stress_scale >= 1 / comfortable_stress))
        return 1;
      return power_of_two_near(stress_scale);
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
        std::abs(log2_strain) <= std::log2(comfortable_stress) ?
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
