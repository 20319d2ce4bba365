#ifndef coulomb_adapt_solvers_matrix_rows_h
#define coulomb_adapt_solvers_matrix_rows_h

#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <Epetra_CrsMatrix.h>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * Call f(column, value) for the stored entries of a locally owned row
   * of @p matrix, through Epetra's row view: deal.II's Trilinos matrix
   * iterators copy the row at every step, which made assembly loops over
   * rows quadratic.
   */
  template <typename Function>
  void
  for_each_entry(const TrilinosWrappers::SparseMatrix &matrix,
                 const types::global_dof_index         row,
                 const Function                       &f)
  {
    const Epetra_CrsMatrix &A         = matrix.trilinos_matrix();
    const int               local_row = A.RowMap().LID(static_cast<int>(row));
    Assert(local_row >= 0, ExcInternalError());
    int     n_entries;
    double *values;
    int    *local_columns;
    A.ExtractMyRowView(local_row, n_entries, values, local_columns);
    for (int e = 0; e < n_entries; ++e)
      f(static_cast<types::global_dof_index>(A.ColMap().GID(local_columns[e])),
        values[e]);
  }
} // namespace coulomb_adapt

#endif
