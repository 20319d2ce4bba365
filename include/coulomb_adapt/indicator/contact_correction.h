#ifndef coulomb_adapt_indicator_contact_correction_h
#define coulomb_adapt_indicator_contact_correction_h

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/indicator/bernstein_contact_traction.h>
#include <coulomb_adapt/indicator/contact_error.h>

#include <array>
#include <optional>
#include <vector>

namespace coulomb_adapt
{
  /** How the corrected contact traction R_c loads the bodies. */
  enum class ContactLoadForm
  {
    /** As in the contact solve: D R_c on the slave nodes, M^T lambda_c on
     * the master nodes (R_c with Wohlmuth's dual basis). The recovery
     * estimators (zz, spr) use it: with R_c = R_h it returns U_h. */
    mortar,
    /** int R_c phi_i with R_c in the slave basis's Bernstein form
     * (contact_traction_at()), the same field on both sides (body 2 at the
     * projected points). The CRE estimator uses it: this R_c lies in the
     * Coulomb cone between the nodes, so the equilibrated stress can carry it
     * as Neumann data. */
    consistent
  };

  /** The corrected FE solution of theory.md section 3.2. */
  struct CorrectedContactSolution
  {
    /** True when R_h was already in the Coulomb cone: the corrected
     * fields are the FE fields and no second solve was done. */
    bool skipped = true;
    /** ||R_c - R_h|| / ||R_h|| in the lumped L2(Gamma_c) norm. */
    double relative_change = 0;
    /** Slave nodes whose reaction the projection moved. */
    unsigned int n_projected_nodes = 0;
    /** The largest move of a nodal reaction, relative to the largest
     * nodal reaction. */
    double largest_nodal_change = 0;
    /** True when the projection moved reactions, but relative_change is
     * below the contact solve's accepted residual: the corrected problem
     * would return U_h to the solve's accuracy, so it was not solved
     * (skipped is true as well). */
    bool within_solve_accuracy = false;
    /** Largest nodal penetration of W_c (mm), clipped by the contact term;
     * 0 if none. */
    double max_penetration = 0;
    /** U_c of body b (0: body 1, 1: body 2): the corrected displacement
     * if a corrected solve was done, else the body's FE solution (not
     * copied). Both with the ghost entries of the body's locally relevant
     * DoFs, which the cells' stresses read. */
    const TrilinosWrappers::MPI::Vector &
    displacement(const unsigned int b) const
    {
      return skipped ? *fe_displacement[b] : corrected_displacement[b];
    }
    /** The bodies' FE solutions U_h (owned by the bodies). */
    std::array<const TrilinosWrappers::MPI::Vector *, 2> fe_displacement{};
    /** U_c of both bodies when the corrected problem was solved, with
     * ghost entries; empty otherwise. */
    std::array<TrilinosWrappers::MPI::Vector, 2> corrected_displacement;
    /** R_c (as lambda_c = -R_c) and W_c at the slave nodes; with the
     * consistent load form R_c's coefficients in the Bernstein basis of
     * quadratic segments (bernstein_contact_traction.h). */
    std::vector<ContactNodeFields> fields;
    /** With the consistent load form on quadratic segments: how R_c's
     * Bernstein coefficients were made (bernstein_contact_traction.h). */
    std::optional<BernsteinContactTraction::Report> bernstein;
  };

  /**
   * Project the nodal reactions of the contact solution onto the Coulomb
   * cone K_mu and, if that changed any of them, solve the corrected problem:
   * each body in equilibrium under its own data and the prescribed contact
   * traction (R_c on body 1, -R_c on body 2), applied in the same mortar
   * form as in the contact solve (D R_c on the slave nodes, M^T lambda_c on
   * the master nodes). With R_c = R_h that problem returns U_h exactly,
   * which is why the solve can be skipped when nothing moved, and also
   * when the reactions moved, in the norm of relative_change, by less
   * than the solve's accepted residual (ContactSolution::
   * accepted_residual()): reactions outside the cone by that little are
   * the Newton iteration's own inaccuracy (it accepted them), and the
   * load of the corrected problem would differ from U_h's by as little.
   * (The consistent load form always solves.)
   *
   * A body whose supports do not hold all its rigid motions (body 1 of
   * `blocks` is held by contact alone) is singular under prescribed
   * tractions: its load is projected onto the range of the stiffness (the
   * part of R_c that the body cannot balance is removed), the free rigid
   * modes are pinned for the solve, and U_c - U_h is made orthogonal to
   * them, so the correction adds no rigid motion.
   */
  CorrectedContactSolution
  correct_contact_solution(
    const ElasticBody              &slave,
    const ElasticBody              &master,
    const ContactSolution          &contact,
    const double                    friction_coefficient,
    const parameters::LinearSolver &solver_parameters,
    const ContactLoadForm           load_form = ContactLoadForm::mortar);

  /** The same, for given nodal contact states on @p mortar (the
   * solver's, or modified ones in tests), solved to the accepted residual
   * @p negligible_change (0: any move beyond round-off is solved). */
  CorrectedContactSolution
  correct_contact_solution(
    const ElasticBody                   &slave,
    const ElasticBody                   &master,
    const MortarInterface               &mortar,
    const std::vector<ContactNodeState> &states,
    const double                         friction_coefficient,
    const parameters::LinearSolver      &solver_parameters,
    const ContactLoadForm                load_form = ContactLoadForm::mortar,
    const double                         negligible_change = 0);

  /** The contact traction on body 1, R = -lambda, at the points of
   * MortarInterface::overlap_quadrature(): the polynomial with the nodal
   * values of @p fields as its coefficients in the slave segments'
   * Bernstein basis (on linear segments the standard basis), which lies
   * in the Coulomb cone wherever the nodal values do (body 2 carries -R
   * at the projected points). */
  std::vector<Tensor<1, 2>>
  contact_traction_at(const MortarInterface                            &mortar,
                      const std::vector<ContactNodeFields>             &fields,
                      const std::vector<MortarInterface::OverlapPoint> &points);

  /** Gauss points per overlap for the consistent contact load and the
   * Neumann data of the equilibrated stress: exact for R (degree p) times
   * a polynomial of degree p + 3 on both sides. */
  unsigned int
  contact_traction_points_per_overlap(const unsigned int degree);

  /** The Euclidean projection of (lambda_n, lambda_t) onto the cone
   * lambda_n >= 0, |lambda_t| <= mu lambda_n (R in K_mu). */
  std::array<double, 2>
  project_onto_coulomb_cone(const double lambda_n,
                            const double lambda_t,
                            const double mu);
} // namespace coulomb_adapt

#endif
