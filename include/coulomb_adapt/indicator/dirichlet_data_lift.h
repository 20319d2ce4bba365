#ifndef coulomb_adapt_indicator_dirichlet_data_lift_h
#define coulomb_adapt_indicator_dirichlet_data_lift_h

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>

#include <string>

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
   *   r = N_a N_b g(N_b),   g(t) = d(x(t)) / (t (1 - t)),
   * N_a, N_b the cell's linear (bilinear) vertex functions, which vanish
   * on every other face and give t (1 - t) on this one (t = N_b along it),
   * x(t) the face's point at t (d vanishes at the vertices, which are
   * nodes of u_c, so g is bounded). r is continuous (zero on every face
   * but the Dirichlet ones) and meets the data exactly; g and its
   * derivative are taken at each quadrature point from u_D, its gradient
   * (the data's Function must provide it) and u_c. Then
   *   ||sigma - sigma_c|| <= ||sigma - sigma(u^)|| + ||sigma(r)||
   *                       <= ||sigma^ - sigma_c|| + 2 ||sigma(r)||,
   * the hypercircle of u^ and sigma^ in the middle (energy norms). The
   * local problems measure sigma^ - sigma(u^) directly
   * (LocalNeumannProblem::set_kinematic_lift()), so the bound is
   *   ||sigma - sigma_c|| <= ||sigma^ - sigma(u^)|| + ||sigma(r)||,
   * r's energy counted once beside the minimised estimate, not twice.
   */
  class DirichletDataLiftField
  {
  public:
    /** The lift of @p u_kinematic's (ghosted) misfit to @p body's
     * displacement data; both must outlive this object. The data's
     * gradient is not checked here: check_displacement_data_gradient()
     * does it once per body and estimate. */
    DirichletDataLiftField(const ElasticBody                   &body,
                           const TrilinosWrappers::MPI::Vector &u_kinematic);

    /** Whether the body's data need a lift (not interpolated exactly). */
    bool
    active() const;

    /** grad r (row c: the gradient of component c, physical coordinates)
     * at @p points, given in @p cell's reference coordinates; empty when
     * the cell has no Dirichlet face or the field is not active. Safe to
     * call from several threads. */
    std::vector<Tensor<2, 2>>
    gradients(const DoFHandler<2>::active_cell_iterator &cell,
              const std::vector<Point<2>>               &points) const;

  private:
    const ElasticBody                   &body;
    const TrilinosWrappers::MPI::Vector &u_kinematic;
  };

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
   * interpolated exactly. The lift's energy is integrated by quadrature
   * (exact for the part of degree p + 2; an earlier version interpolated g
   * by a polynomial of degree p, and its ||sigma(r)|| differed by at most
   * 0.4 % on the manufactured meshes).
   */
  DirichletDataLift
  dirichlet_data_lift(const ElasticBody                   &body,
                      const TrilinosWrappers::MPI::Vector &u_kinematic);

  /**
   * Why component @p c of @p data cannot serve the lift on the Dirichlet
   * face from @p a to @p b: at a quarter and at three quarters of it, its
   * gradient()'s derivative along the face differs from the central
   * difference of its values (relative 1e-5 of the larger of the two and
   * of how much the data vary along the face); empty when they agree. The
   * lift reads the data's gradient (g' above), and deal.II's
   * Function::gradient() returns zero in release builds where a scene
   * does not implement it: without this check such a scene's lift would
   * be silently wrong.
   */
  std::string
  data_gradient_mismatch(const Function<2> &data,
                         const unsigned int c,
                         const Point<2>    &a,
                         const Point<2>    &b);

  /**
   * data_gradient_mismatch() on every Dirichlet face this rank owns of a
   * body whose data need the lift (DirichletDataLiftField::active()); a
   * mismatch on any rank stops the run on every rank, with a message
   * naming @p body and the way out. Nothing to check (and no
   * communication) where the data are interpolated exactly. The cre
   * estimate calls it once per body before the lift is built.
   */
  void
  check_displacement_data_gradient(const ElasticBody &body);
} // namespace coulomb_adapt

#endif
