#include <coulomb_adapt/indicator/spr_patch_fit.h>

#include <cmath>

namespace coulomb_adapt
{
  namespace spr
  {
    // Solve the normal equations of one patch for the highest degree <= p
    // its sampling points determine.
    //
    // The matrix is first scaled to unit diagonal. Changing the length
    // unit (or scaling the local coordinates by a cell size) multiplies
    // each monomial by a power of the scale, a diagonal change of basis
    // that this equilibration undoes exactly: the fit and the rank
    // decision are independent of the mesh size, and the coordinates need
    // no further scaling. A Cholesky factorisation without pivoting, in
    // the degree order of the monomials, then says how much of each
    // monomial is not explained by the lower ones; the first small pivot
    // ends the monomials the patch determines (e.g. two centroids on a
    // Q1 boundary fix a constant, not a plane).
    PatchFit
    fit_patch(const std::vector<double> &entries,
              const PatchLayout         &layout,
              const unsigned int         degree,
              const Point<2>            &centre)
    {
      // cond(equilibrated matrix) up to ~1e8 is accepted.
      const double pivot_tolerance = 1e-8;

      const unsigned int                  n = layout.n_fit_monomials();
      std::array<double, max_n_monomials> scale{};
      for (unsigned int k = 0; k < n; ++k)
        {
          const double diagonal = entries[layout.matrix_entry(k, k)];
          scale[k]              = diagonal > 0 ? 1. / std::sqrt(diagonal) : 0.;
        }

      // On the stack: one fit per vertex.
      std::array<std::array<double, max_n_monomials>, max_n_monomials>
                 cholesky_entries{};
      const auto cholesky = [&](const unsigned int i,
                                const unsigned int j) -> double & {
        return cholesky_entries[i][j];
      };
      unsigned int n_determined = 0;
      for (unsigned int k = 0; k < n && scale[k] > 0; ++k)
        {
          double pivot = 1.;
          for (unsigned int j = 0; j < k; ++j)
            pivot -= cholesky(k, j) * cholesky(k, j);
          if (!(pivot > pivot_tolerance))
            break;
          cholesky(k, k) = std::sqrt(pivot);
          for (unsigned int i = k + 1; i < n; ++i)
            {
              double a =
                scale[i] * entries[layout.matrix_entry(k, i)] * scale[k];
              for (unsigned int j = 0; j < k; ++j)
                a -= cholesky(i, j) * cholesky(k, j);
              cholesky(i, k) = a / cholesky(k, k);
            }
          ++n_determined;
        }

      PatchFit fit;
      fit.centre = centre;
      if (n_determined == 0)
        return fit;
      fit.has_fit = true;
      fit.degree  = degree;
      while (n_monomials(fit.degree) > n_determined)
        --fit.degree;
      const unsigned int m = n_monomials(fit.degree);

      // L L^T y = S b, coefficients S y.
      for (unsigned int c = 0; c < 3; ++c)
        {
          std::array<double, max_n_monomials> y{};
          for (unsigned int i = 0; i < m; ++i)
            {
              double r = scale[i] * entries[layout.rhs_entry(c, i)];
              for (unsigned int j = 0; j < i; ++j)
                r -= cholesky(i, j) * y[j];
              y[i] = r / cholesky(i, i);
            }
          for (unsigned int i = m; i-- > 0;)
            {
              double r = y[i];
              for (unsigned int j = i + 1; j < m; ++j)
                r -= cholesky(j, i) * y[j];
              y[i] = r / cholesky(i, i);
            }
          for (unsigned int i = 0; i < m; ++i)
            fit.coefficients[i][c] = scale[i] * y[i];
        }
      return fit;
    }
  } // namespace spr
} // namespace coulomb_adapt
