#ifndef coulomb_adapt_core_units_h
#define coulomb_adapt_core_units_h

namespace coulomb_adapt
{
  /**
   * The load scale of a run (issue 21, theory.md section 6 Homogeneity):
   * the program solves, estimates and adapts the problem with every load
   * divided by a factor P, and multiplies what it reports by P (lengths
   * of the deformation, stresses, tractions and forces) or P^2 (energies).
   *
   * P is an exact power of 2, so that dividing and multiplying by it is
   * exact in floating point (no digit is lost while the numbers stay
   * normal): the scaled problem is the problem a user would have given in
   * moderate units. P = 1 for ordinary loads, whose runs do not change.
   */
  namespace units
  {
    /** Stresses of the loads within [1 / comfortable_stress,
     * comfortable_stress] (MPa) are solved as given (P = 1). Beyond, the
     * error indicator's squares of stresses and the energies come near the
     * ends of the range of doubles (1e-308 ... 1e308): above 1e154 the
     * squares overflow, below 1e-154 they lose their digits, and stress
     * concentrations (Hertz's peak, corners) lie some orders above the
     * loads' scale. */
    constexpr double comfortable_stress = 1e100;

    /** Without scaling, stresses within [1 / accepted_stress,
     * accepted_stress] still keep the indicator's squares finite and
     * normal (the check after the solve uses this range). */
    constexpr double accepted_stress = 1e120;

    /** The power of 2 nearest to @p magnitude (> 0, finite) in the sense
     * of the exponent: 2^round(log2 magnitude). */
    double
    power_of_two_near(const double magnitude);

    /** The load scale P for loads whose stress scale is @p stress_scale
     * (MPa, >= 0): 1 within the comfortable range (and for no load at
     * all), else power_of_two_near(stress_scale). */
    double
    load_scale_for(const double stress_scale);

    /** @p scaled_value (a quantity of the scaled problem that scales with
     * the loads to the power @p power: 1 for displacements, stresses,
     * forces, 2 for energies) multiplied by P^power, if that is a finite
     * number and, for powers above 1, P^power a normal double (products
     * that underflow are the physical values rounded to the doubles);
     * else returns false and leaves @p physical alone: the value is then
     * reported in its scaled form. */
    bool
    to_physical(const double scaled_value,
                const double load_scale,
                const int    power,
                double      &physical);
  } // namespace units
} // namespace coulomb_adapt

#endif
