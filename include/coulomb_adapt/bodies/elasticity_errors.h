#ifndef coulomb_adapt_bodies_elasticity_errors_h
#define coulomb_adapt_bodies_elasticity_errors_h

#include <deal.II/base/function.h>

#include <coulomb_adapt/bodies/elastic_body.h>

namespace coulomb_adapt
{
  /** Norms of the error u_h - u of a body's displacement. */
  struct ElasticityErrors
  {
    /** ||u_h - u||_{L2} (mm^2). */
    double l2;
    /** Energy norm sqrt( int (eps_h - eps) : C : (eps_h - eps) ), the norm
     * the error indicator estimates (sqrt(N mm)). */
    double energy;
    /** Energy norm of u itself, for relative errors. */
    double energy_of_exact;
  };

  /**
   * Integrate the error of @p body's displacement against @p exact (which
   * must provide values and gradients) with a quadrature two orders above
   * the element's, summed over all ranks.
   */
  ElasticityErrors
  compute_elasticity_errors(const ElasticBody &body, const Function<2> &exact);
} // namespace coulomb_adapt

#endif
