#ifndef coulomb_adapt_solvers_threaded_matrix_product_h
#define coulomb_adapt_solvers_threaded_matrix_product_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Vector.h>

#include <memory>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * y = A x for a Trilinos matrix, its rows shared among the threads
   * deal.II may use. Epetra's own product runs on one thread per rank;
   * the estimator's truncated CG, whose matrix has ~30 entries per row, is
   * otherwise serial (benchmarks/effectivity).
   *
   * The contact solve's Krylov + AMG iterations multiply by the bodies'
   * stiffness matrices (ReducedMatrix) in GMRES and in the fine level's
   * smoother, the estimator's truncated CG by its parameters' matrix.
   *
   * Each row is summed entry by entry in the order Epetra stores it,
   * as Epetra's kernel (epetra_dcrsmv) does, so the product is bit for
   * bit Epetra's on any number of threads. A matrix whose storage is not
   * optimised (no contiguous rows) or whose range is not its row map is
   * multiplied by Epetra itself.
   */
  class ThreadedMatrixProduct
  {
  public:
    /** @p A must outlive this object and keep its pattern. */
    explicit ThreadedMatrixProduct(const TrilinosWrappers::SparseMatrix &A);

    /** The same for an Epetra matrix. */
    explicit ThreadedMatrixProduct(const Epetra_CrsMatrix &A);

    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

    /** y = A x for one vector each, x on A's domain map, y on its range
     * map (views welcome; y must not be x, unlike for Epetra). */
    void
    vmult(Epetra_MultiVector &y, const Epetra_MultiVector &x) const;

    /** Whether vmult() runs on the threads (false: Epetra multiplies). */
    bool
    threaded() const;

  private:
    const Epetra_CrsMatrix &A;
    // The rows in compressed form (null: Epetra multiplies).
    int    *row_starts = nullptr;
    int    *columns    = nullptr;
    double *values     = nullptr;
    int     n_rows     = 0;
    // x on the matrix's column map, where that differs from its domain
    // (the ghost entries of other ranks' columns).
    mutable std::unique_ptr<Epetra_Vector> x_columns;
  };
} // namespace coulomb_adapt

#endif
