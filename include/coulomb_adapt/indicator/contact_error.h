#ifndef coulomb_adapt_indicator_contact_error_h
#define coulomb_adapt_indicator_contact_error_h

#include <deal.II/grid/cell_id.h>

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/contact/mortar_interface.h>

#include <array>
#include <map>
#include <vector>

namespace coulomb_adapt
{
  /** The contact fields of the indicator at one slave node, in the sign
   * convention of the solver (lambda = -R). */
  struct ContactNodeFields
  {
    /** lambda_n = -R_n (MPa). */
    double pressure = 0;
    /** lambda_t = -R_t (MPa). */
    double tangential_traction = 0;
    /** Normal gap (mm): -W_n relative to the initial gap; < 0 is
     * penetration. */
    double gap = 0;
    /** W_t (mm). */
    double slip = 0;
  };

  /** The contact term of the indicator, theory.md section 3.4. */
  struct ContactErrorTerm
  {
    /** int_{Gamma_c} c(W, R) (N per unit thickness), counted once. */
    double integral = 0;
    /** int over the contact faces of each slave / master cell: every piece
     * of the interface is counted once on each side, so the two maps
     * together sum to 2 * integral, the factor 2 of the seed's (3-10). */
    std::map<CellId, double> slave_cells;
    std::map<CellId, double> master_cells;
    /** int psi_j c / int psi_j at slave node j (MPa mm): the density of
     * the contact term along the interface, with psi_j the hat function
     * on linear segments and a Bernstein polynomial (>= 0) on quadratic
     * ones. */
    std::vector<double> nodal_density;
  };

  /**
   * Integrate the De Saxce bipotential gap
   *
   *   c(W, R) = mu |R_n| |W_t| + R_t W_t + R_n min(W_n, 0)
   *
   * over the part of Gamma_c where the bodies face each other (the mortar
   * overlaps). The fields are the nodal values of @p fields interpolated
   * with the standard (non-negative) slave basis, so that a nodal R in the
   * Coulomb cone stays in it between the nodes; W_n = -gap, and
   * min(W_n, 0) clips what penetration the weak mortar condition leaves
   * between the nodes (theory.md section 3.2).
   *
   * |R_n|, |W_t| and the clipping make c only piecewise polynomial: each
   * overlap is split at the zeros of lambda_n, W_t and the gap, and each
   * piece integrated exactly with Gauss points, so that both sides see the
   * same numbers and sum(epsilon_E^2) = epsilon^2 holds to round-off.
   */
  ContactErrorTerm
  integrate_contact_error(const MortarInterface                &mortar,
                          const std::vector<ContactNodeFields> &fields,
                          const double friction_coefficient);

  /** lambda_n of each of @p fields. */
  std::vector<double>
  nodal_pressures(const std::vector<ContactNodeFields> &fields);

  /**
   * The contact term of the bound for mu = 0: c = lambda_n g, with the
   * pressure lambda_n of @p fields (the equilibrated stress's, its nodal
   * values as the coefficients of the slave basis's Bernstein polynomials,
   * so >= 0 between the nodes, slave_bernstein_interpolant()) and the pointwise
   * gap g of the displacements (>= 0 where they are admissible; a
   * penetration left is counted as 0, and reported by the caller), on
   * every overlap, per slave and master cell as integrate_contact_error()
   * gives it (without its nodal densities).
   */
  ContactErrorTerm
  pressure_gap_term(
    const MortarInterface                                      &mortar,
    const std::vector<ContactNodeFields>                       &fields,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements);

  /**
   * The most negative pressure of @p fields between the slave nodes (the
   * equilibrated stress's, slave_bernstein_interpolant(), sampled as the
   * gaps are), relative to the largest nodal pressure; 0 if none. The
   * bound needs sigma^'s pressure >= 0: it is wherever the nodal values
   * are, on quadratic segments too (their Lagrange interpolant overshot
   * below 0 where the zone opens, hertz P2 by 2.2 % of the largest
   * pressure, until 2026-12-01), so this is a check.
   */
  double
  pressure_gap_negative_pressure(const MortarInterface                &mortar,
                                 const std::vector<ContactNodeFields> &fields);
} // namespace coulomb_adapt

#endif
