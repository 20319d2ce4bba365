#ifndef coulomb_adapt_bodies_rigid_motion_gram_h
#define coulomb_adapt_bodies_rigid_motion_gram_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * Which rigid motions of a 2D body a set of constraints holds. A rigid
   * motion u(x) = (a - r (x_2 - c_2), b + r (x_1 - c_1)) about a centre c
   * has the coordinates (a, b, r); a constraint that fixes d . u(x) (a
   * Dirichlet component, a contact node's normal or tangent) is the row
   * (d_1, d_2, d x (x - c)), and the constraints hold every rigid motion if
   * their Gram matrix, the sum of the rows' outer products, is regular.
   */

  /** Add the constraint on d . u(@p x), @p d = @p direction, to @p gram
   * (rotation about @p centre). */
  void
  add_rigid_motion_constraint(FullMatrix<double> &gram,
                              const Tensor<1, 2> &direction,
                              const Point<2>     &x,
                              const Point<2>     &centre);

  /** The Gram matrix of the same constraints with the rotation about
   * centre + @p shift instead of centre: the rotation about the new centre
   * is the old one plus the translation (shift_2, -shift_1). */
  FullMatrix<double>
  move_rotation_centre(const FullMatrix<double> &gram,
                       const Tensor<1, 2>       &shift);

  /**
   * Whether the constraints in @p gram hold every rigid motion. The
   * translations: the Hadamard ratio of their 2 x 2 block (rows of unit
   * directions). The rotation: what is left of it once the translations
   * are projected out (the Schur complement, the same about every centre),
   * relative to the rotation's own diagonal entry, i.e. to the round-off
   * of the computation. That entry is smallest, and the test sharpest, for
   * a centre near the constraints: a cluster of contact nodes far from the
   * centre otherwise looks like a single point.
   */
  bool
  holds_all_rigid_motions(const FullMatrix<double> &gram);

  /** Whether the constraints in @p gram hold the translation along the
   * unit vector @p direction: t . G_tt t, the sum of the squared
   * components along t of the constrained directions, above 1e-6 of the
   * number of constraints (for Dirichlet components: some constrained
   * component has |t_c| > 1e-3). */
  bool
  holds_translation_along(const FullMatrix<double> &gram,
                          const Tensor<1, 2>       &direction);
} // namespace coulomb_adapt

#endif
