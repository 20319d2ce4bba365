#include <deal.II/base/exceptions.h>
#include <deal.II/base/parallel.h>

#include <coulomb_adapt/solvers/threaded_matrix_product.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>

namespace coulomb_adapt
{
  namespace
  {
    // Rows per task: ~30 entries each, so a task is ~10^5 flops.
    constexpr unsigned int rows_per_task = 2048;
  } // namespace



  ThreadedMatrixProduct::ThreadedMatrixProduct(
    const TrilinosWrappers::SparseMatrix &A)
    : A(A)
  {
    // Epetra hands out the pointers to its compressed rows only through a
    // non-const member; nothing is written through them.
    Epetra_CrsMatrix &matrix =
      const_cast<Epetra_CrsMatrix &>(A.trilinos_matrix());
    // The kernel writes y on the row map and reads x on the column map:
    // without an exporter the range is the row map.
    if (!matrix.StorageOptimized() || matrix.Exporter() != nullptr ||
        matrix.ExtractCrsDataPointers(row_starts, columns, values) != 0)
      {
        row_starts = nullptr;
        return;
      }
    n_rows = matrix.NumMyRows();
    if (matrix.Importer() != nullptr)
      x_columns = std::make_unique<Epetra_Vector>(matrix.ColMap());
  }



  void
  ThreadedMatrixProduct::vmult(TrilinosWrappers::MPI::Vector       &dst,
                               const TrilinosWrappers::MPI::Vector &src) const
  {
    if (row_starts == nullptr)
      {
        A.vmult(dst, src);
        return;
      }
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    Assert(src.trilinos_vector().Map().SameAs(matrix.DomainMap()),
           ExcMessage("x is not on the matrix's domain"));
    Assert(dst.trilinos_vector().Map().SameAs(matrix.RangeMap()),
           ExcMessage("y is not on the matrix's range"));
    const double *x = src.trilinos_vector()[0];
    if (x_columns)
      {
        AssertThrow(x_columns->Import(src.trilinos_vector(),
                                      *matrix.Importer(),
                                      Insert) == 0,
                    ExcMessage("matrix product: importing x failed"));
        x = x_columns->Values();
      }
    double *const y = dst.trilinos_vector()[0];
    parallel::apply_to_subranges(
      0,
      n_rows,
      [&](const int begin, const int end) {
        for (int i = begin; i < end; ++i)
          {
            double sum = 0.;
            for (int k = row_starts[i]; k < row_starts[i + 1]; ++k)
              sum += values[k] * x[columns[k]];
            y[i] = sum;
          }
      },
      rows_per_task);
  }



  bool
  ThreadedMatrixProduct::threaded() const
  {
    return row_starts != nullptr;
  }
} // namespace coulomb_adapt
