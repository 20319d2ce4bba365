#ifndef coulomb_adapt_indicator_narrow_opening_h
#define coulomb_adapt_indicator_narrow_opening_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/mortar_interface.h>

#include <map>
#include <optional>
#include <vector>

namespace coulomb_adapt
{
  /**
   * An opening of one body narrower than its cells (kinematic_admissibility.h,
   * doc/indicator.md section 4c). The bound needs some H^1 field delta,
   * zero on the supports, whose rise of the gap covers every penetration
   * of U_c; it need not lie in the judged mesh's FE space. In the judged
   * space the opening spans at least a cell at every opened node, so its
   * work S against the contact pressure grows with the cells' width,
   * while in 2D the energy of a lift of height d over a width w is of
   * order d^2 whatever w. Here delta lives on a copy of the cells around
   * the deepest penetrations (those with a vertex on a contact face
   * where the gap of U_c is below -threshold), refined until a fine face
   * is an eighth of the penetrating width: its trace on the contact faces
   * covers the gap's deficit fine face by fine face (the gap of degree-1
   * elements is linear along an overlap, so each face's largest deficit is
   * at its ends or an overlap's), it is zero on the patch's boundary inside
   * the body and on supports and loaded faces, free on traction-free
   * faces, and of least energy inside. b^2 and S are then exact integrals
   * on the fine cells.
   *
   * Degree-1 elements on straight contact faces only (on curved ones the
   * initial gap is not linear along an overlap), and only where no
   * constrained DoF (a support, a held line, a hanging node) touches the
   * patch: a seed face that would include one is left to the nodal
   * opening.
   */
  /** Where a narrow opening was built, as the log and summary.json say. */
  struct NarrowOpeningPatch
  {
    /** The body opened (0: slave, 1: master). */
    unsigned int side = 0;
    /** How often the patch's cells were bisected, and how many there
     * are (the judged ones and the fine ones). */
    unsigned int refinements = 0;
    unsigned int cells       = 0;
    unsigned int fine_cells  = 0;
  };

  struct NarrowOpening
  {
    NarrowOpeningPatch patch;
    /** ||sigma(delta)||^2 on every active cell of the body (0 outside the
     * patch and on cells this rank does not own), and its sum (N per unit
     * thickness). */
    Vector<double> energy;
    double         norm_squared = 0;
    /** S = int sigma(U_c) : eps(delta) - int f . delta over the patch. */
    double work = 0;

    /** The rise of the gap at @p point from delta (mm). */
    double
    rise(const MortarInterface               &mortar,
         const MortarInterface::OverlapPoint &point) const;

    /** The points of the overlaps at the fine trace's nodes, where the gap
     * of U_c + delta has its kinks (weight 0). */
    std::vector<MortarInterface::OverlapPoint>
    kinks(const MortarInterface &mortar) const;

    /** The trace on one fine contact face, between its parameters on its
     * segment (the judged face): delta at both ends. */
    struct TraceFace
    {
      double       begin;
      double       end;
      Tensor<1, 2> delta_begin;
      Tensor<1, 2> delta_end;
    };
    /** Per segment of the side's list that the patch touches. */
    std::map<unsigned int, std::vector<TraceFace>> trace;
  };

  /**
   * The narrow opening of side @p side (0: slave, 1: master) of @p mortar
   * for the corrected displacements @p displacements (with ghost
   * entries): it covers the penetration on every contact face of that side
   * where U_c penetrates by more than @p threshold (mm). Empty when no
   * such face qualifies (degree 2, curved faces, constrained DoFs, no
   * penetration above the threshold) or when the patch's solve fails.
   * The patch is bisected at most @p max_refinements times (4: 16 fine
   * faces per judged one; on the punch's remeshed mesh 3, 4 and 5 gave
   * epsilon 6.566, 6.405 and 6.385 %, 5 at 3.5 times the cost of 4).
   */
  std::optional<NarrowOpening>
  make_narrow_opening(
    const MortarInterface                                      &mortar,
    const std::array<const ElasticBody *, 2>                   &bodies,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements,
    const unsigned int                                          side,
    const double                                                threshold,
    const unsigned int max_refinements = 4);
} // namespace coulomb_adapt

#endif
