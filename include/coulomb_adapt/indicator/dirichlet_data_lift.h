#ifndef coulomb_adapt_indicator_dirichlet_data_lift_h
#define coulomb_adapt_indicator_dirichlet_data_lift_h

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>

namespace coulomb_adapt
{
  /**
   * The CRE's bound (theory.md section 7) needs a kinematic side that
   * meets the displacement data. The FE solution u_c meets them at its
   * nodes only: where the data are not polynomials of its degree (the
   * manufactured scene's sinusoid, BodyDescription::
   * displacement_data_interpolated_exactly), it misses them between the
   * nodes of each Dirichlet face, and a minimisation over sigma^ can
   * exploit that (the relaxed equilibration gave estimates 0.5-3.5 %
   * below the exact error there).
   *
   * So u^ = u_c + r, r a lift of the data's interpolation error d = u_D -
   * u_c: on a cell with a Dirichlet face of vertices a, b,
   *   r = N_a N_b S(N_b),
   * N_a, N_b the cell's linear (bilinear) vertex functions, which vanish
   * on every other face and give t (1 - t) on this one (t = N_b along it),
   * and S the polynomial of degree p that interpolates d / (t (1 - t)) at
   * p + 1 interior points of the face (d vanishes at the vertices, which
   * are nodes of u_c). r is continuous (zero on every face but the
   * Dirichlet ones), meets the data up to an interpolation error two
   * degrees higher than u_c's, and
   *   ||sigma - sigma_c|| <= ||sigma - sigma(u^)|| + ||sigma(r)||
   *                       <= ||sigma^ - sigma_c|| + 2 ||sigma(r)||,
   * the hypercircle of u^ and sigma^ in the middle (energy norms).
   */
  struct DirichletDataLift
  {
    /** ||sigma(r)||^2 on each active cell of the body (0 on cells this
     * rank does not own and on cells without a Dirichlet face). */
    Vector<double> squared;
    /** Their sum over all ranks (N per unit thickness). */
    double norm_squared = 0;
  };

  /**
   * The lift of the interpolation error of @p body's displacement data by
   * @p u_kinematic (with ghost entries). Zero where the data are
   * interpolated exactly.
   */
  DirichletDataLift
  dirichlet_data_lift(const ElasticBody                   &body,
                      const TrilinosWrappers::MPI::Vector &u_kinematic);
} // namespace coulomb_adapt

#endif
