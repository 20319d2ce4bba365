#ifndef coulomb_adapt_contact_reduced_matrix_h
#define coulomb_adapt_contact_reduced_matrix_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <coulomb_adapt/solvers/threaded_matrix_product.h>

#include <Epetra_BasicRowMatrix.h>

#include <map>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The reduced matrix A = Z~^T K Z of the eliminated contact system
   * without a copy of K: A differs from K = diag(K^1, K^2) only in the
   * rows near the contact interface (EliminatedOperator), so only those
   * are stored; every other row is read from the bodies' K^1, K^2, with
   * their stored zeros left out as the explicit construction leaves them
   * out. ML takes it as an Epetra_RowMatrix (its rows through
   * ExtractMyRowCopy), the Krylov solvers through Multiply. The full
   * copy of A was about 0.23 kB per DoF at the AMG setup, where the
   * contact solve has its peak (benchmarks/adaptive_run, "Memory").
   *
   * Rows and products are those of the stored matrix: the same entries in
   * the same order (one rank: to the last bit), so the AMG hierarchy and
   * the Krylov iterates are unchanged.
   *
   * K^1 and K^2 are read, not copied: they must outlive this object.
   */
  class ReducedMatrix : public Epetra_BasicRowMatrix
  {
  public:
    /** Rows of A by global index (owned, ascending columns). */
    using Rows =
      std::map<types::global_dof_index,
               std::vector<std::pair<types::global_dof_index, double>>>;

    /** @p explicit_rows: the rows of A that differ from K's; @p offset:
     * the shift of body 2's indices in the combined space @p owned. */
    ReducedMatrix(const TrilinosWrappers::SparseMatrix &K1,
                  const TrilinosWrappers::SparseMatrix &K2,
                  const types::global_dof_index         offset,
                  const IndexSet                       &owned,
                  const MPI_Comm                        communicator,
                  const Rows                           &explicit_rows);

    int
    ExtractMyRowCopy(int     row,
                     int     length,
                     int    &n_entries,
                     double *values,
                     int    *columns) const override;
    int
    NumMyRowEntries(int row, int &n_entries) const override;
    /** Entry views: there is no matrix to view (Epetra's defaults that
     * need them, scaling, are not used). */
    int
    ExtractMyEntryView(int, double *&, int &, int &) override
    {
      return -1;
    }
    int
    ExtractMyEntryView(int, double const *&, int &, int &) const override
    {
      return -1;
    }
    /** Y = A X: K^1 and K^2's products, then the explicit rows. */
    int
    Multiply(bool                      transpose,
             const Epetra_MultiVector &X,
             Epetra_MultiVector       &Y) const override;

    /** Number of rows stored (this rank). */
    std::size_t
    n_explicit_rows() const
    {
      return explicit_local_rows.size();
    }

  private:
    /** The explicit row of local row @p row, or -1. */
    int
    explicit_index(const int row) const;

    const Epetra_CrsMatrix &K1;
    const Epetra_CrsMatrix &K2;
    /** Their products on deal.II's threads, bit for bit Epetra's: the
     * largest single part of an AMG-preconditioned step (15.7 % of the
     * CPU time of the example at 0.25 %, benchmarks/adaptive_run). */
    ThreadedMatrixProduct K1_product;
    ThreadedMatrixProduct K2_product;
    /** Rows of body 1 on this rank (its rows come first locally). */
    int n_local_1;
    /** Local column of K^1 (K^2) -> local column of A. */
    std::vector<int> columns_1;
    std::vector<int> columns_2;

    /** The explicit rows in compressed row storage, local indices. */
    std::vector<int>         explicit_local_rows;
    std::vector<std::size_t> explicit_start;
    std::vector<int>         explicit_columns;
    std::vector<double>      explicit_values;
  };
} // namespace coulomb_adapt

#endif
