#ifndef coulomb_adapt_tests_dovetail_blade_h
#define coulomb_adapt_tests_dovetail_blade_h

#include <deal.II/base/point.h>

#include <cmath>
#include <vector>

// The blade of prm/meshes/dovetail.geo in closed form: its outline,
// counterclockwise, with flanks at @p alpha to the x axis from the root's
// corners (+-10, 2) up to the neck x = +-6, and the area and centroid
// from the outline (the shoelace formulas), for the centrifugal force the
// dovetail tests check the contact force against.
struct DovetailBlade
{
  explicit DovetailBlade(const double alpha)
  {
    const double t = std::tan(alpha);
    corners        = {{-10, 0},
                      {10, 0},
                      {10, 2},
                      {6, 2 + 4 * t},
                      {6, 40},
                      {-6, 40},
                      {-6, 2 + 4 * t},
                      {-10, 2}};
    dealii::Tensor<1, 2> first_moment;
    for (unsigned int i = 0; i < corners.size(); ++i)
      {
        const dealii::Point<2> &a = corners[i],
                               &b = corners[(i + 1) % corners.size()];
        const double cross        = a[0] * b[1] - b[0] * a[1];
        area += cross / 2;
        first_moment += cross / 6 * (a + b);
      }
    centroid = dealii::Point<2>(first_moment / area);
  }

  std::vector<dealii::Point<2>> corners;
  double                        area = 0;
  dealii::Point<2>              centroid;
};

#endif
