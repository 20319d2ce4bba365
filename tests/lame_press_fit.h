// Lame's contact pressure of the press fit in prm/meshes/press_fit*.geo,
// shared by the press-fit tests.
#ifndef coulomb_adapt_tests_lame_press_fit_h
#define coulomb_adapt_tests_lame_press_fit_h

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
  } // namespace testing
} // namespace coulomb_adapt

#endif
