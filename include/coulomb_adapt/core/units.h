#ifndef coulomb_adapt_core_units_h
#define coulomb_adapt_core_units_h

#include <string>

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
    /** Problems whose stress scale, moduli, strain scale (stress over
     * modulus) and energy density scale (stress times strain) all lie
     * within [1 / comfortable_scale, comfortable_scale] (MPa, or no unit)
     * are solved as given (P = D = 1). Beyond, they are solved scaled. The
     * bound is set by the field files, not by the doubles: deal.II's
     * output patches round every field to 32-bit floats (1.2e-38 ...
     * 3.4e38), and stress concentrations (Hertz's peak, corners) lie some
     * orders above the loads' scale. The doubles alone would allow far
     * more (the indicator squares stresses: 1e154). */
    constexpr double comfortable_scale = 1e30;

    /** Whether @p magnitude (>= 0) is 0 or within [1 / comfortable_scale,
     * comfortable_scale]. */
    bool
    is_comfortable(const double magnitude);

    /** "1e-30 ... 1e30" for comfortable_scale, for messages. */
    std::string
    comfortable_range();

    /** Stresses within [1 / accepted_stress, accepted_stress] keep the
     * indicator's squares finite and normal: the check after the solve
     * (app/finiteness.h) stops a run whose stresses leave it. */
    constexpr double accepted_stress = 1e120;

    /** The power of 2 nearest to @p magnitude (> 0, finite) in the sense
     * of the exponent: 2^round(log2 magnitude). */
    double
    power_of_two_near(const double magnitude);

    /** Whether a problem with stress scale @p stress_scale (MPa, >= 0)
     * and moduli @p E1, @p E2 (MPa) can be solved as given: all its
     * scales are comfortable (is_comfortable). */
    bool
    solvable_as_given(const double stress_scale,
                      const double E1,
                      const double E2);

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
     * load); D = 1 while the strain scale P / modulus is comfortable
     * (is_comfortable; stresses and moduli are divided alike, displacements
     * stay: exact also with an initial gap), else the power of 2 near the
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
