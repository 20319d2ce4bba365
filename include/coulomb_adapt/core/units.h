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

    /** Moduli within [1 / comfortable_modulus, comfortable_modulus] (MPa)
     * are used as given (the modulus scale is 1). Beyond, they are divided
     * by a power of 2 with the loads (scales_for_moduli). */
    constexpr double comfortable_modulus = 1e100;

    /** Strains (stress scale over modulus scale) within [1 /
     * largest_strain, largest_strain] can be solved: displacements are
     * scaled so that the scaled problem has moderate strains, and the
     * physical displacements, ε times the bodies' size, stay finite
     * doubles for the report. Beyond, no scaling helps: an error before
     * solving. */
    constexpr double largest_strain = 1e300;

    /** The scales of a run: loads and stresses are divided by @p stress
     * (P), displacements (and gaps, slips) by @p displacement (D), moduli
     * by their ratio P / D. All exact powers of 2; P = D = 1 for
     * ordinary problems. With moduli as given, D = P. */
    struct Scales
    {
      double stress       = 1;
      double displacement = 1;

      double
      modulus() const
      {
        return stress / displacement;
      }
    };

    /** How a reported quantity scales: stresses, tractions, forces and
     * moments with P; displacements, gaps, slips with D; energies and
     * products of a stress and a length (the contact term's density) with
     * P D; energy norms with sqrt(P D). */
    enum class Kind
    {
      stress,
      displacement,
      energy,
      energy_norm
    };

    /** The scales for moduli outside the comfortable range: loads' stress
     * scale @p stress_scale (MPa, >= 0) and the reference modulus
     * @p modulus (MPa, the geometric mean of the bodies' moduli). P is the
     * power of 2 near the stress scale (near the modulus if there is no
     * load); D = 1 while the strain scale P / modulus is within 1e-100 ...
     * 1e100 (stresses and moduli are divided alike, displacements stay:
     * exact also with an initial gap), else the power of 2 near the
     * strain. Returns false if the strain is beyond [1 / largest_strain,
     * largest_strain]. */
    bool
    scales_for_moduli(const double stress_scale,
                      const double modulus,
                      Scales      &scales);

    /** @p scaled_value, a quantity of kind @p kind, times its factor of
     * @p scales, with the rules of to_physical below (the factor of
     * energies must be a normal double). */
    bool
    to_physical(const double  scaled_value,
                const Scales &scales,
                const Kind    kind,
                double       &physical);

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
