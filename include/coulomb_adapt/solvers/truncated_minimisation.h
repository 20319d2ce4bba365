#ifndef coulomb_adapt_solvers_truncated_minimisation_h
#define coulomb_adapt_solvers_truncated_minimisation_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * How a truncated minimisation ended.
   */
  struct TruncatedMinimisation
  {
    unsigned int steps = 0;
    // Whether the stopping test was met (false: max_steps reached; the
    // iterate is still the best one found).
    bool converged = false;
    // J(0) - J(x) (>= 0) and the value J(x) itself, with J as below.
    double decrease = 0;
    double value    = 0;
  };

  /**
   * Minimise J(x) = offset + x.A x - 2 b.x (A SPD) by CG preconditioned
   * with @p P, from x = 0, and stop when the last @p window steps together
   * lowered J by less than @p relative_tolerance J(x).
   *
   * For when J itself is the result, not x: CG lowers J at every step (by
   * a_k r_k.z_k, which it knows without extra work), so J(x) is known at
   * every step, and the decrease over the last few steps is the
   * Hestenes-Stiefel estimate of what is left, J(x) - min J (Strakos and
   * Tichy, 2002): what the stopping test bounds. The test is relative to
   * J, so x scales with b and the number of steps does not change when
   * b, A and offset are scaled together.
   */
  TruncatedMinimisation
  minimise_by_truncated_cg(const TrilinosWrappers::SparseMatrix &A,
                           TrilinosWrappers::MPI::Vector        &x,
                           const TrilinosWrappers::MPI::Vector  &b,
                           const AdditiveSchwarzPreconditioner  &P,
                           const double                          offset,
                           const double       relative_tolerance,
                           const unsigned int window,
                           const unsigned int max_steps);
} // namespace coulomb_adapt

#endif
