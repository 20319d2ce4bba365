#ifndef coulomb_adapt_contact_contact_state_h
#define coulomb_adapt_contact_contact_state_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  class MortarInterface;

  /** The contact sets of theory.md section 2: a slave node is open,
   * sticks or slips. */
  enum class ContactStatus
  {
    open,
    stick,
    slip
  };

  std::string
  to_string(const ContactStatus status);

  /** The contact state at one slave node after the solve. */
  struct ContactNodeState
  {
    Point<2>     position;
    Tensor<1, 2> normal;
    Tensor<1, 2> tangent;
    /** Mortar weight D_jj (mm). */
    double weight;
    /** lambda_n = -R_n >= 0 (MPa). */
    double pressure;
    /** lambda_t = -R_t (MPa): the traction body 2 receives from body 1
     * along t; body 1 receives its opposite. */
    double tangential_traction;
    /** Normal gap (mm), >= 0 when open. */
    double gap;
    /** Tangential jump W_t = (u^1 - u^2) . t (mm). */
    double slip;
    /** W_t gained in the last load step (mm): the slip of the static
     * problem, the increment of a quasi-static one (the slip of the
     * incremental Coulomb law and of its error indicator). */
    double slip_increment;
    /** Whether the master surface lies opposite the node (covers its
     * support); if not, the node cannot touch and gap/slip are not
     * defined (reported as 0). */
    bool facing_master;
    /** A Dirichlet condition holds the node along the contact surface (a
     * roller on a symmetry line): it replaces the tangential contact
     * condition, the node sticks by construction (slips, without
     * friction), and lambda_t = 0, the support taking the tangential
     * reaction. */
    bool          held_tangentially = false;
    ContactStatus status;
    /** Sign of the slip direction (slip nodes). */
    int slip_sign;
  };

  /**
   * A solved contact interface as the later phases read it (the error
   * indicator, mesh adaptation, output): the mortar interface and the
   * state of each of its slave nodes. ContactSolver is one; the phases
   * that only read the solution depend on this header, not on the
   * solver.
   */
  class ContactSolution
  {
  public:
    virtual ~ContactSolution() = default;

    virtual const MortarInterface &
    mortar_interface() const = 0;

    virtual const std::vector<ContactNodeState> &
    node_states() const = 0;

    /** The complementarity residual, relative to the largest contact
     * pressure, that the solve accepted as converged: max(Contact/
     * Tolerance, the multipliers' round-off floor). Contact fields that
     * differ by less are the same solution to the solve's accuracy. */
    virtual double
    accepted_residual() const = 0;
  };
} // namespace coulomb_adapt

#endif
