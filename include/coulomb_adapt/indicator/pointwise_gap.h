#ifndef coulomb_adapt_indicator_pointwise_gap_h
#define coulomb_adapt_indicator_pointwise_gap_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/contact/mortar_interface.h>

#include <array>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The gap between the bodies between the mortar's nodes. The mortar
   * keeps one weighted gap per slave node >= 0; between the nodes the
   * gap has kinks at the master nodes and at the ends of the master's
   * contact zone, so a displacement the mortar accepts can penetrate
   * there. The CRE's contact terms and its kinematic side
   * (kinematic_admissibility.h) need the gap pointwise.
   */

  /**
   * Where to sample the gap on each overlap of segments of @p degree: the
   * ends (the gap of linear segments is linear in between, so its
   * smallest value is at an end) and, for quadratic segments, enough
   * points between them to see a parabola's minimum to a fraction of its
   * depth. interior_gap_minima() adds the minima between them.
   */
  QGaussLobatto<1>
  gap_sample_rule(const unsigned int degree);

  /**
   * Where the gap of the nodal displacements @p slave_values,
   * @p master_values of quadratic segments is smallest inside each
   * overlap: points the samples of gap_sample_rule() can miss (a
   * parabola's minimum between two of 9 Gauss-Lobatto points lies below
   * both). On a straight overlap (MortarInterface::overlap_is_straight())
   * the gap is a parabola in the overlap's parameter: its vertex, where it
   * opens upwards and lies inside, exactly. On a curved one it is smooth
   * but no polynomial: the minimum near the smallest interior sample, by
   * successive parabolic interpolation. As points of weight 0 (samples,
   * not quadrature points); none for linear segments, whose gap is
   * smallest at an overlap's end.
   */
  std::vector<MortarInterface::OverlapPoint>
  interior_gap_minima(const MortarInterface           &mortar,
                      const std::vector<Tensor<1, 2>> &slave_values,
                      const std::vector<Tensor<1, 2>> &master_values);

  /**
   * The normal in which the gap is measured at @p point: the slave
   * segment's normal, on curved segments the interpolated nodal normal,
   * as the mortar measures the initial gap and the weighted jumps.
   */
  Tensor<1, 2>
  gap_normal(const MortarInterface               &mortar,
             const MortarInterface::OverlapPoint &point);

  /**
   * The polynomial at @p point whose coefficients in the slave segment's
   * Bernstein basis are @p nodal_values (one per slave node): >= 0
   * wherever they are, on quadratic segments too. On linear segments it
   * is the interpolant with the standard basis. The contact traction of
   * the equilibrated stress has this form (contact_traction_at()).
   */
  double
  slave_bernstein_interpolant(const MortarInterface               &mortar,
                              const MortarInterface::OverlapPoint &point,
                              const std::vector<double> &nodal_values);

  /**
   * The normal gap g = (y - x) . n - n . (u^1(x) - u^2(y)) at each of
   * @p points, from the nodal displacements of the slave and master
   * nodes (@p slave_values, @p master_values, as
   * MortarInterface::gather_nodal_displacements() gives them), with n =
   * gap_normal().
   */
  std::vector<double>
  pointwise_gaps(const MortarInterface                            &mortar,
                 const std::vector<MortarInterface::OverlapPoint> &points,
                 const std::vector<Tensor<1, 2>>                  &slave_values,
                 const std::vector<Tensor<1, 2>> &master_values);

  /** The same from the bodies' displacements (with ghost entries). */
  std::vector<double>
  pointwise_gaps(
    const MortarInterface                                      &mortar,
    const std::vector<MortarInterface::OverlapPoint>           &points,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements);
} // namespace coulomb_adapt

#endif
