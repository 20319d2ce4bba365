#include <coulomb_adapt/bodies/rigid_motion_gram.h>

#include <array>

namespace coulomb_adapt
{
  void
  add_rigid_motion_constraint(FullMatrix<double> &gram,
                              const Tensor<1, 2> &direction,
                              const Point<2>     &x,
                              const Point<2>     &centre)
  {
    const Tensor<1, 2>          arm = x - centre;
    const std::array<double, 3> row = {
      {direction[0],
       direction[1],
       -direction[0] * arm[1] + direction[1] * arm[0]}};
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        gram(a, b) += row[a] * row[b];
  }



  FullMatrix<double>
  move_rotation_centre(const FullMatrix<double> &gram,
                       const Tensor<1, 2>       &shift)
  {
    // G' = B^T G B, the columns of B the new motions in the old coordinates.
    FullMatrix<double> B(3, 3);
    B(0, 0) = B(1, 1) = B(2, 2) = 1;
    B(0, 2)                     = shift[1];
    B(1, 2)                     = -shift[0];
    FullMatrix<double> GB(3, 3), moved(3, 3);
    gram.mmult(GB, B);
    B.Tmmult(moved, GB);
    return moved;
  }



  bool
  holds_all_rigid_motions(const FullMatrix<double> &gram)
  {
    const double a = gram(0, 0), b = gram(0, 1), d = gram(1, 1);
    const double det = a * d - b * b;
    if (!(a > 0 && d > 0 && det > 1e-10 * a * d))
      return false;
    const double g0 = gram(0, 2), g1 = gram(1, 2);
    const double rotation_left =
      gram(2, 2) - (d * g0 * g0 - 2 * b * g0 * g1 + a * g1 * g1) / det;
    return gram(2, 2) > 0 && rotation_left > 1e-10 * gram(2, 2);
  }



  bool
  holds_translation_along(const FullMatrix<double> &gram,
                          const Tensor<1, 2>       &direction)
  {
    double along = 0;
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int b = 0; b < 2; ++b)
        along += direction[a] * gram(a, b) * direction[b];
    return along > 1e-6 * (gram(0, 0) + gram(1, 1));
  }
} // namespace coulomb_adapt
