#ifndef coulomb_adapt_solvers_symmetric_direct_solver_h
#define coulomb_adapt_solvers_symmetric_direct_solver_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * Solve A x = b for a symmetric positive definite @p A by MUMPS's
   * LDL^T factorisation of its lower triangle.
   *
   * Trilinos' Amesos_Mumps (TrilinosWrappers::SolverDirect) hands MUMPS the
   * whole matrix as unsymmetric with MUMPS's automatic ordering: an LU
   * factorisation, twice the flops and the memory of LDL^T. On the CRE
   * estimator's parameters' system (a fourth-order operator on a P2-like
   * pattern, where the factorisation is nearly all the time: dense
   * fronts in BLAS) the symmetric factorisation is what makes the direct
   * solve affordable. The analysis is sequential (MUMPS's ordering of the
   * gathered pattern), the factorisation on every rank of @p A's communicator; b
   * is gathered on rank 0 and x scattered back, so the result does not
   * depend on the number of ranks beyond round-off.
   *
   * Throws with MUMPS's error code (INFOG(1), INFOG(2)) when the
   * factorisation fails, e.g. on a matrix that is not positive definite.
   */
  void
  solve_symmetric_positive_definite(const TrilinosWrappers::SparseMatrix &A,
                                    TrilinosWrappers::MPI::Vector        &x,
                                    const TrilinosWrappers::MPI::Vector  &b);
} // namespace coulomb_adapt

#endif
