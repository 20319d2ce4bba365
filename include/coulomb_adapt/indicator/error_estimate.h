#ifndef coulomb_adapt_indicator_error_estimate_h
#define coulomb_adapt_indicator_error_estimate_h

#include <deal.II/base/timer.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/indicator/contact_correction.h>
#include <coulomb_adapt/indicator/contact_error.h>
#include <coulomb_adapt/indicator/recovered_stress.h>

#include <array>
#include <memory>

namespace coulomb_adapt
{
  /** The indicator of theory.md section 3 for one solution. */
  struct ErrorEstimate
  {
    /** Global relative error epsilon (3-13). */
    double epsilon = 0;
    /** Its parts: epsilon^2 = sum_l epsilon_volume[l]^2 +
     * epsilon_contact^2. */
    std::array<double, 2> epsilon_volume = {{0, 0}};
    double                epsilon_contact = 0;
    /** D^2 = sum_l ||sigma~ + sigma_c||^2 (N per unit thickness). */
    double normalisation_squared = 0;
    /** epsilon_E per active cell of each body (entries of locally owned
     * cells), and epsilon_E^2 / |E| (1/mm^2). */
    std::array<Vector<float>, 2> indicator;
    std::array<Vector<float>, 2> density;
    /** e_E^2 = epsilon_E^2 D^2 per cell, unrounded, for the sums. */
    std::array<Vector<double>, 2> contribution_squared;
    StressRecoveryMethod          recovery = StressRecoveryMethod::l2_projection;
    /** The corrected solution (for scenes with contact). */
    CorrectedContactSolution correction;
    bool                     has_contact = false;
    ContactErrorTerm         contact;
    /** sigma~ of each body. */
    std::array<std::unique_ptr<RecoveredStress>, 2> recovered;
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
   * With a @p timer, the three phases are timed in its sections
   * "error indicator: correction" (the corrected contact fields),
   * "error indicator: smoothing" (sigma_c at the quadrature points, the
   * stress space and the recovery) and "error indicator: contributions"
   * (volume and contact terms, epsilon and epsilon_E).
   */
  ErrorEstimate
  estimate_error(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolution *                   contact,
                 const double                              friction_coefficient,
                 const StressRecoveryMethod                recovery,
                 const parameters::LinearSolver &          solver_parameters,
                 TimerOutput *                             timer = nullptr);

  /** For a per-cell quantity on the boundary (the contact term): the
   * locally owned boundary cells' CellId and active index. Interior cells
   * are left out: a CellId costs more than the rest of the indicator's
   * per-cell work. */
  std::map<CellId, unsigned int>
  owned_boundary_cell_indices(const ElasticBody &body);
} // namespace coulomb_adapt

#endif
