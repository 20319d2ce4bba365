#ifndef coulomb_adapt_indicator_error_estimate_h
#define coulomb_adapt_indicator_error_estimate_h

#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/core/error_estimator.h>
#include <coulomb_adapt/indicator/contact_correction.h>
#include <coulomb_adapt/indicator/contact_error.h>
#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/narrow_opening.h>
#include <coulomb_adapt/indicator/recovered_stress.h>

#include <array>
#include <memory>
#include <optional>

namespace coulomb_adapt
{
  /** The indicator of theory.md section 3 for one solution. */
  struct ErrorEstimate
  {
    /** Global relative error epsilon (3-13). */
    double epsilon = 0;
    /** Its parts: epsilon^2 = sum_l epsilon_volume[l]^2 +
     * epsilon_contact^2. */
    std::array<double, 2> epsilon_volume  = {{0, 0}};
    double                epsilon_contact = 0;
    /** D^2 = sum_l ||sigma~ + sigma_c||^2 (N per unit thickness). */
    double normalisation_squared = 0;
    /** epsilon_E per active cell of each body (entries of locally owned
     * cells), and epsilon_E^2 / |E| (1/mm^2). */
    std::array<Vector<float>, 2> indicator;
    std::array<Vector<float>, 2> density;
    /** e_E^2 = epsilon_E^2 D^2 per cell, unrounded, for the sums. */
    std::array<Vector<double>, 2> contribution_squared;
    StressRecoveryMethod recovery = StressRecoveryMethod::l2_projection;
    /** Which estimator computed it. */
    ErrorEstimator estimator = ErrorEstimator::zz;
    /** Wall time of computing it (s; with a known correction, without
     * solving the corrected problem). */
    double wall_time = 0;
    /** cre only: the equilibration's defects (equilibrated_stress.h), the
     * larger of the two bodies'. */
    double node_system_defect   = 0;
    double local_problem_defect = 0;
    /** cre: the largest reaction of a node held by the scene's point
     * constraints that sigma^ does not carry, relative to the largest
     * element residual. Held lines ('Hold centre line', 'Hold axis') are
     * carried (held_reactions.h); a mesh file's point supports are not. */
    double uncarried_held_reaction = 0;
    /** cre: sigma^ misses a held node's reaction beyond round-off, so it
     * is not exactly statically admissible. */
    bool
    misses_held_reaction() const
    {
      return uncarried_held_reaction > 1e-8;
    }
    /** cre: the estimate with the classical edge tractions (closest to the
     * averaged traction), before its free parameters are optimised, and
     * the CG steps of that optimisation (0: not optimised). */
    double                  epsilon_before_optimisation = 0;
    types::global_dof_index optimisation_parameters     = 0;
    /** cre with the relaxed equilibration: the truncated CG's steps (the
     * larger of the two bodies'; 0: solved directly or not optimised). */
    unsigned int optimisation_steps = 0;
    /** cre: whether a body's relaxed system was too large for the exact
     * minimisation ('CRE exact minimisation up to') and was minimised by
     * the truncated CG instead. */
    bool exact_minimisation_too_large = false;
    /** cre, per body: whether the relaxed equilibration modes were used
     * (equilibrated_stress_errors()). */
    std::array<bool, 2> relaxed_equilibration = {{false, false}};
    /** cre: whether 'CRE relaxed equilibration' asked for them. */
    bool relaxed_equilibration_requested = false;
    /** cre: whether a body's displacement data are not interpolated
     * exactly by the FE space and were not lifted either ('CRE lift of
     * displacement data' false): its kinematic side misses them between
     * the nodes, so the estimate is not a proven bound. */
    bool displacement_data_unlifted = false;
    /** cre: the estimate comes from local problems this much higher in
     * degree than the minimisation's ('CRE evaluation degree increase'),
     * and per body whether the optimised tractions, evaluated there, were
     * above the classical ones, which were then kept. */
    unsigned int        evaluation_degree_increase = 0;
    std::array<bool, 2> classical_tractions_kept   = {{false, false}};
    /** cre: the largest pointwise penetration of U_c between the mortar's
     * nodes (mm; 0 if none) and where; for mu = 0, where the estimate is a
     * bound, whether the interface nodes were opened to remove it, how
     * many (slave, master), the penetration left (no free node could
     * open it), ||sigma(u^ - U_c)|| / D and 2 S / D^2, S the work of
     * U_c's stress on the opening beyond the loads
     * (kinematic_admissibility.h);
     * and the most negative pressure of sigma^ between the nodes relative
     * to the largest (P2/Q2 interpolants; the bound needs it >= 0). */
    double                      penetration = 0;
    Point<2>                    penetration_at;
    bool                        opening_applied       = false;
    std::array<unsigned int, 2> opened_nodes          = {{0, 0}};
    double                      penetration_after     = 0;
    double                      epsilon_opening       = 0;
    double                      opening_work_relative = 0;
    /** Where a body was opened narrower than its cells (narrow_opening.h);
     * empty where it was not. */
    std::optional<NarrowOpeningPatch> narrow_opening;
    double                            negative_pressure = 0;
    /** cre where the displacement data are not interpolated exactly:
     * ||sigma(r)|| / D of their lift r (dirichlet_data_lift.h), which the
     * bound adds to ||sigma^ - sigma(u_c + r)||; 0 elsewhere. */
    double epsilon_dirichlet_lift = 0;
    /** cre on quadratic contact segments: how sigma^'s contact traction
     * was put in the Coulomb cone (bernstein_contact_traction.h). */
    std::optional<BernsteinContactTraction::Report> bernstein_traction;
    /** The corrected solution (for scenes with contact). */
    CorrectedContactSolution correction;
    bool                     has_contact = false;
    ContactErrorTerm         contact;
    /** sigma~ of each body. */
    std::array<std::unique_ptr<RecoveredStress>, 2> recovered;
  };

  /**
   * How an estimate is computed, not what: the options every estimator
   * (estimate_error(), estimate_error_cre()) takes after its inputs.
   */
  struct ErrorEstimateOptions
  {
    /** With a timer, the three phases are timed in its sections
     * "error indicator: correction" (the corrected contact fields),
     * "error indicator: smoothing" (sigma_c at the quadrature points, the
     * stress space and the recovery; for cre "error indicator:
     * equilibration") and "error indicator: contributions" (volume and contact
     * terms, epsilon and epsilon_E). */
    TimerOutput *timer = nullptr;
    /** The seed's corrected solution of this same contact solution if
     * another estimator has already computed it (`Compare estimators`);
     * it is then copied instead of solved again. */
    const CorrectedContactSolution *known_correction = nullptr;
  };



  /**
   * Correct the contact fields (if there is a contact interface), recover
   * sigma~ from sigma_c on each body and sum the element contributions
   *
   *   e_E^2 = int_E (sigma~ - sigma_c)^T K^-1 (sigma~ - sigma_c)
   *           + int_{Gamma_c cap dE} c(W_c, R_c)
   *
   * into epsilon_E = e_E / D and epsilon (theory.md 3.4, 3.5). @p contact
   * (the solved contact interface) may be null (no contact zone).
   *
   * @p options: the timer and a correction already computed
   * (ErrorEstimateOptions); neither changes what is computed.
   */
  ErrorEstimate
  estimate_error(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolution                    *contact,
                 const double                              friction_coefficient,
                 const StressRecoveryMethod                recovery,
                 const parameters::LinearSolver           &solver_parameters,
                 const ErrorEstimateOptions               &options = {});

  /**
   * The estimator @p estimator (zz, spr or cre) for the current solution:
   * zz and spr as above; cre is the error in constitutive relation of
   * theory.md section 7 (estimate_error_cre).
   */
  ErrorEstimate
  estimate_error(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolution                    *contact_solver,
                 const double                              friction_coefficient,
                 const ErrorEstimator                      estimator,
                 const parameters::ErrorIndicator         &indicator_parameters,
                 const parameters::LinearSolver           &solver_parameters,
                 const ErrorEstimateOptions               &options = {});

  /**
   * The error in constitutive relation (theory.md section 7): the
   * corrected solution with the contact traction R_c in its consistent
   * form (ContactLoadForm::consistent, always solved when there is contact
   * pressure), a statically admissible stress sigma^ per body by the
   * element equilibration technique with R_c (body 1) and -R_c (body 2) as
   * Neumann data on Gamma_c, local problems of degree p + @p degree_increase,
   * and
   *   e_E^2 = ||sigma^ - sigma_c||^2_E + int_{Gamma_c cap dE} c(W_c, R_c),
   *   D^2 = sum_l ||sigma^ + sigma_c||^2.
   * Conforming meshes only (no hanging nodes).
   */
  ErrorEstimate
  estimate_error_cre(const std::array<const ElasticBody *, 2> &bodies,
                     const ContactSolution                    *contact_solver,
                     const double                    friction_coefficient,
                     const unsigned int              degree_increase,
                     const bool                      optimise_tractions,
                     const bool                      relax_equilibration,
                     const CreMinimisation          &minimisation,
                     const parameters::LinearSolver &solver_parameters,
                     const ErrorEstimateOptions     &options = {});

  /** The common start of every estimator on a contact scene: the
   * corrected contact fields of theory.md section 3, those of
   * @p options.known_correction when the caller already has them (compare
   * mode), else solved. */
  CorrectedContactSolution
  corrected_contact_fields(const std::array<const ElasticBody *, 2> &bodies,
                           const ContactSolution                    &contact,
                           const double                    friction_coefficient,
                           const parameters::LinearSolver &solver_parameters,
                           const ErrorEstimateOptions     &options);

  /** The common end of every estimator: the contact term added to the
   * contact cells of each side (the factor 2 of (3-10)), the seed's
   * normalisation D^2, epsilon, its parts, and epsilon_E and the density
   * per cell, from the volume terms already in
   * estimate.contribution_squared. */
  void
  finish_error_estimate(const std::array<const ElasticBody *, 2> &bodies,
                        const std::array<double, 2> &volume_squared,
                        const double                 normalisation_squared,
                        ErrorEstimate               &estimate);

  /** For a per-cell quantity on the boundary (the contact term): the
   * locally owned boundary cells' CellId and active index. Interior cells
   * are left out: a CellId costs more than the rest of the indicator's
   * per-cell work. */
  std::map<CellId, unsigned int>
  owned_boundary_cell_indices(const ElasticBody &body);
} // namespace coulomb_adapt

#endif
