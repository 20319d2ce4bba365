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
    : ThreadedMatrixProduct(A.trilinos_matrix())
  {}



  ThreadedMatrixProduct::ThreadedMatrixProduct(const Epetra_CrsMatrix &A)
    : A(A)
  {
    // Epetra hands out the pointers to its compressed rows only through a
    // non-const member; nothing is written through them.
    Epetra_CrsMatrix &matrix = const_cast<Epetra_CrsMatrix &>(A);
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
    vmult(dst.trilinos_vector(), src.trilinos_vector());
  }



  void
  ThreadedMatrixProduct::vmult(Epetra_MultiVector       &y_vector,
                               const Epetra_MultiVector &x_vector) const
  {
    AssertThrow(x_vector.NumVectors() == 1 && y_vector.NumVectors() == 1,
                ExcMessage("matrix product: one vector at a time"));
    if (row_starts == nullptr)
      {
        const int error = A.Multiply(false, x_vector, y_vector);
        AssertThrow(error == 0, ExcMessage("Epetra's matrix product failed"));
        return;
      }
    // Rows are written while other rows still read x: y must not be x.
    AssertThrow(x_vector[0] != y_vector[0],
                ExcMessage("matrix product: y must not be x"));
    Assert(x_vector.Map().SameAs(A.DomainMap()),
           ExcMessage("x is not on the matrix's domain"));
    Assert(y_vector.Map().SameAs(A.RangeMap()),
           ExcMessage("y is not on the matrix's range"));
    const double *x = x_vector[0];
    if (x_columns)
      {
        AssertThrow(x_columns->Import(x_vector, *A.Importer(), Insert) == 0,
                    ExcMessage("matrix product: importing x failed"));
        x = x_columns->Values();
      }
    double *const y = y_vector[0];
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
