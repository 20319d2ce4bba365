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
  } // namespace units
} // namespace coulomb_adapt
