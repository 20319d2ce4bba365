#ifndef coulomb_adapt_indicator_quadrature_stress_h
#define coulomb_adapt_indicator_quadrature_stress_h

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>

#include <vector>

namespace coulomb_adapt
{
  /** sigma as the three components (xx, yy, xy) that the indicator stores
   * (raw stress at quadrature points, recovered stress). */
  inline Tensor<1, 3>
  stress_components(const SymmetricTensor<2, 2> &sigma)
  {
    return Tensor<1, 3>({sigma[0][0], sigma[1][1], sigma[0][1]});
  }

  /** The inverse of stress_components. */
  inline SymmetricTensor<2, 2>
  stress_tensor(const Tensor<1, 3> &components)
  {
    SymmetricTensor<2, 2> sigma;
    sigma[0][0] = components[0];
    sigma[1][1] = components[1];
    sigma[0][1] = components[2];
    return sigma;
  }



  /**
   * The stress sigma_c = K eps(u) of one body and the weights JxW at the
   * points of the body's cell quadrature, for every locally owned cell.
   *
   * The ZZ projection (its right-hand sides and mass matrix) and the volume
   * terms of the indicator both integrate over these points. Evaluated
   * once, in one FEValues pass, instead of once per use with two FEValues
   * each (displacement and stress space): on meshes of 10^3 DoFs the
   * per-cell mapping and gradient work is most of the indicator's time.
   *
   * Owned cells are numbered 0, 1, ... in the order of the active cell
   * iterators (of any DoFHandler on the body's triangulation, they all
   * walk the cells in the same order); every pass that reads this data
   * counts the owned cells the same way.
   */
  class QuadratureStress
  {
  public:
    /** Evaluate on @p body's current mesh for @p displacement (a ghosted
     * vector of the body's displacement space). Keeps references to both. */
    QuadratureStress(const ElasticBody                   &body,
                     const TrilinosWrappers::MPI::Vector &displacement);
    /** The same at the points of @p quadrature instead (SPR samples the
     * Gauss points of order p), with the points' positions if
     * @p with_points. */
    QuadratureStress(const ElasticBody                   &body,
                     const TrilinosWrappers::MPI::Vector &displacement,
                     const Quadrature<2>                 &quadrature,
                     const bool                           with_points);
    /** The reference kept to the displacement must not dangle. */
    QuadratureStress(const ElasticBody &,
                     TrilinosWrappers::MPI::Vector &&) = delete;
    QuadratureStress(const ElasticBody &,
                     TrilinosWrappers::MPI::Vector &&,
                     const Quadrature<2> &,
                     const bool)                       = delete;

    const ElasticBody &
    body() const;

    const TrilinosWrappers::MPI::Vector &
    displacement() const;

    /** Points per cell (the size of the quadrature, by default
     * ElasticBody::cell_quadrature()). */
    unsigned int
    n_points() const;

    /** Locally owned cells: a pass that reads this data must have counted
     * as many. */
    unsigned int
    n_cells() const;

    /** (xx, yy, xy) of sigma_c at point @p q of owned cell number @p cell. */
    const Tensor<1, 3> &
    stress(const unsigned int cell, const unsigned int q) const;

    double
    JxW(const unsigned int cell, const unsigned int q) const;

    /** The position of point @p q of owned cell number @p cell; only if
     * constructed with_points. */
    const Point<2> &
    point(const unsigned int cell, const unsigned int q) const;

  private:
    const ElasticBody                   &body_;
    const TrilinosWrappers::MPI::Vector &displacement_;
    unsigned int                         n_points_;
    std::vector<Tensor<1, 3>>            stresses;
    std::vector<double>                  weights;
    std::vector<Point<2>>                points;
  };
} // namespace coulomb_adapt

#endif
