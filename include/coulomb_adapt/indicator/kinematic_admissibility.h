#ifndef coulomb_adapt_indicator_kinematic_admissibility_h
#define coulomb_adapt_indicator_kinematic_admissibility_h

#include <deal.II/base/point.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/indicator/narrow_opening.h>

#include <array>
#include <optional>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The CRE's bound for mu = 0 (theory.md section 7.4) needs a kinematic
   * side without penetration anywhere on the interface. The mortar method
   * keeps the bodies apart only in the weak sense of its dual basis (one
   * weighted gap per slave node), so between the nodes, where a master
   * node or the end of the master's contact zone falls inside a slave
   * segment, the corrected displacement U_c can penetrate: a flat punch's
   * corner on a remeshed block whose nodes do not meet it
   * (doc/indicator.md section 4c). For a penetrating U_c the hypercircle
   * misses the term 2 int p |g^-| of the exact pressure p, which nothing
   * computable bounds.
   *
   * So interface nodes are opened (moved into their own body, along the
   * normal) just enough to remove every penetration, and the opening is
   * extended into the bodies by least energy: u^ = U_c + delta.
   * Each penetration is removed, worst first, by the nodes that can lift
   * it, the lift shared among them at least cost (in energy and in the
   * contact term it adds).
   * u^ does not penetrate (g(U_c) + rise(delta) >= 0), so the term the
   * hypercircle misses, -int p g(U_c) with p >= 0 the exact pressure, is
   * at most the exact contact traction's work on delta, int p rise(delta)
   * = sum_b int (sigma - sigma_c) : eps(delta_b) + S <= e b + S, with e =
   * ||sigma - sigma_c||, b = ||sigma(delta)|| and S = opening_work;
   * cre_estimate.cc solves the quadratic inequality this gives for e. (It
   * is the same as ||sigma - sigma_c|| <= ||sigma - sigma(u^)|| + b with
   * the hypercircle of u^.)
   */
  struct KinematicAdmissibility
  {
    /** Largest penetration of U_c between the bodies, pointwise on the
     * mortar overlaps (mm); 0 if none beyond round-off. */
    double penetration = 0;
    /** Where (on the slave side) it is largest. */
    Point<2> where;
    /** Whether the nodes were opened (false: measured only). */
    bool opening_applied = false;
    /** Interface nodes opened in each body (0: slave, 1: master). */
    std::array<unsigned int, 2> n_opened_nodes = {{0, 0}};
    /** Largest penetration of u^: 0, unless no free node could lift a
     * point, the step limit (4 per sample point) was reached, or a
     * hanging interface node, which follows its constraint's masters and
     * not the greedy's model of the gaps, was moved down. */
    double penetration_after = 0;
    /** ||sigma(delta)||^2 on each active cell of each body (0 on the cells
     * this rank does not own), and its sum over both bodies and all ranks
     * (N per unit thickness). */
    std::array<Vector<double>, 2> opening_squared;
    double                        opening_norm_squared = 0;
    /** S = sum_b int sigma(U_c) : eps(delta) - l_b(delta), with l_b the
     * body's external load: what U_c's stress does on the opening beyond
     * the loads, the computable part of the exact contact traction's
     * work on it (N per unit thickness). */
    double opening_work = 0;
    /** Where the body was opened narrower than its cells
     * (narrow_opening.h); empty if it was not (not tried, or its bound was
     * not lower than the nodal opening's alone). */
    std::optional<NarrowOpeningPatch> narrow;

    bool
    opened() const
    {
      return n_opened_nodes[0] + n_opened_nodes[1] > 0 || narrow.has_value();
    }
  };

  /**
   * Measure U_c's pointwise penetration (@p displacements of the slave
   * and the master body, with ghost entries) on every overlap of
   * @p mortar, and open interface nodes where it penetrates. @p pressure:
   * the coefficients of the equilibrated stress's pressure lambda_n, one
   * per slave node (Bernstein form, bernstein_contact_traction.h), which
   * the contact term multiplies with the opened gap. The opening is
   * extended into each body by least energy (a linear solve with
   * @p solver_parameters, on the body's stiffness with the interface
   * nodes that face the other side fixed; those beyond its ends, which no
   * gap sees, move freely). Where the penetration is deep, a narrow
   * opening of either body (narrow_opening.h) is tried under it, the
   * nodal opening lifting what it leaves; of these the one with the
   * smallest bound b + sqrt(@p hypercircle_squared + b^2 + 2 S) is
   * returned (@p hypercircle_squared: A^2 + 2 int p^ g+ of U_c). With
   * @p open false (friction: no bound is claimed) the penetration is only
   * measured.
   */
  KinematicAdmissibility
  make_kinematically_admissible(
    const MortarInterface                                      &mortar,
    const std::array<const ElasticBody *, 2>                   &bodies,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements,
    const std::vector<double>                                  &pressure,
    const parameters::LinearSolver &solver_parameters,
    const double                    hypercircle_squared,
    const bool                      open = true);
} // namespace coulomb_adapt

#endif
