#ifndef coulomb_adapt_indicator_spr_patch_fit_h
#define coulomb_adapt_indicator_spr_patch_fit_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The least-squares polynomial of one patch of superconvergent patch
   * recovery (spr_recovery.cc): the monomials, where the normal equations
   * and the fit of one vertex sit among its slots, and the fit itself.
   */
  namespace spr
  {
    constexpr unsigned int max_spr_degree  = 2;
    constexpr unsigned int max_n_monomials = 6;

    constexpr unsigned int
    n_monomials(const unsigned int degree)
    {
      return (degree + 1) * (degree + 2) / 2;
    }

    // 1, dx, dy, dx^2, dx dy, dy^2, in local coordinates d = x - x_vertex.
    // Ordered by degree, so that a fit of lower degree uses the leading
    // rows and columns of the same normal equations.
    inline std::array<double, max_n_monomials>
    monomials(const Tensor<1, 2> &d)
    {
      return {{1., d[0], d[1], d[0] * d[0], d[0] * d[1], d[1] * d[1]}};
    }



    // Where the entries of one vertex sit among its n_entries() slots of
    // the per-vertex vectors. Normal equations: the upper triangle of A^T A
    // (row by row), then A^T b for the components xx, yy, xy. Fit: the
    // coefficients of the three components, the fitted degree + 1 (0: no
    // fit) and a flag for patches that serve as SPR centres.
    class PatchLayout
    {
    public:
      explicit PatchLayout(const unsigned int degree)
        : n(n_monomials(degree))
      {
        Assert(is_centre_entry() < n_entries(), ExcInternalError());
      }

      unsigned int
      n_fit_monomials() const
      {
        return n;
      }
      unsigned int
      matrix_entry(const unsigned int i, const unsigned int j) const
      {
        Assert(i <= j, ExcInternalError());
        return i * n - i * (i - 1) / 2 + (j - i);
      }
      unsigned int
      rhs_entry(const unsigned int component, const unsigned int k) const
      {
        return n * (n + 1) / 2 + component * n + k;
      }
      unsigned int
      coefficient_entry(const unsigned int component,
                        const unsigned int k) const
      {
        return component * n + k;
      }
      unsigned int
      fitted_degree_entry() const
      {
        return 3 * n;
      }
      unsigned int
      is_centre_entry() const
      {
        return 3 * n + 1;
      }
      // Slots per vertex: the normal equations, the larger of the two
      // records.
      unsigned int
      n_entries() const
      {
        return n * (n + 1) / 2 + 3 * n;
      }

    private:
      unsigned int n;
    };



    // The least-squares polynomial of one patch.
    struct PatchFit
    {
      Point<2>                                  centre;
      bool                                      is_centre = false;
      bool                                      has_fit   = false;
      unsigned int                              degree    = 0;
      std::array<Tensor<1, 3>, max_n_monomials> coefficients;

      Tensor<1, 3>
      value(const Point<2> &x) const
      {
        const auto   m = monomials(x - centre);
        Tensor<1, 3> sigma;
        for (unsigned int k = 0; k < n_monomials(degree); ++k)
          sigma += coefficients[k] * m[k];
        return sigma;
      }
    };



    /** The polynomial of degree <= @p degree fitted to the normal
     * equations in @p entries (laid out by @p layout): the highest degree
     * the patch's sampling points determine (spr_patch_fit.cc says how). */
    PatchFit
    fit_patch(const std::vector<double> &entries,
              const PatchLayout         &layout,
              const unsigned int         degree,
              const Point<2>            &centre);
  } // namespace spr
} // namespace coulomb_adapt

#endif
