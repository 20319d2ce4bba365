#include <coulomb_adapt/contact/reduced_matrix.h>

#include <Epetra_Import.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <memory>
#include <tuple>

namespace coulomb_adapt
{
  namespace
  {
    // The owned columns first, in the row map's order, then the others
    // by owning rank and index: the layout of Epetra's FillComplete, and
    // the one ML assumes (its ghost exchange takes the first columns for
    // the owned entries of a vector).
    Epetra_Map
    column_map(const Epetra_Map &row_map, std::vector<int> ghosts)
    {
      std::sort(ghosts.begin(), ghosts.end());
      ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
      std::vector<int> owners(ghosts.size()), unused(ghosts.size());
      row_map.RemoteIDList(ghosts.size(),
                           ghosts.data(),
                           owners.data(),
                           unused.data());
      std::vector<std::pair<int, int>> by_owner;
      for (std::size_t g = 0; g < ghosts.size(); ++g)
        by_owner.emplace_back(owners[g], ghosts[g]);
      std::sort(by_owner.begin(), by_owner.end());

      std::vector<int> columns(row_map.MyGlobalElements(),
                               row_map.MyGlobalElements() +
                                 row_map.NumMyElements());
      for (const auto &[owner, column] : by_owner)
        columns.push_back(column);
      return Epetra_Map(-1,
                        static_cast<int>(columns.size()),
                        columns.data(),
                        row_map.IndexBase(),
                        row_map.Comm());
    }

    // Columns of @p K (shifted by @p offset) that @p row_map does not own.
    void
    append_ghost_columns(const Epetra_CrsMatrix &K,
                         const int               offset,
                         const Epetra_Map       &row_map,
                         std::vector<int>       &ghosts)
    {
      for (int c = 0; c < K.ColMap().NumMyElements(); ++c)
        {
          const int column = K.ColMap().GID(c) + offset;
          if (!row_map.MyGID(column))
            ghosts.push_back(column);
        }
    }

    // Local column of K -> local column of the combined matrix.
    std::vector<int>
    combined_columns(const Epetra_CrsMatrix &K,
                     const int               offset,
                     const Epetra_Map       &columns)
    {
      std::vector<int> local(K.ColMap().NumMyElements());
      for (int c = 0; c < K.ColMap().NumMyElements(); ++c)
        local[c] = columns.LID(K.ColMap().GID(c) + offset);
      return local;
    }
  } // namespace



  ReducedMatrix::ReducedMatrix(const TrilinosWrappers::SparseMatrix &K1,
                               const TrilinosWrappers::SparseMatrix &K2,
                               const types::global_dof_index         offset,
                               const IndexSet                       &owned,
                               const MPI_Comm communicator,
                               const Rows    &explicit_rows)
    : Epetra_BasicRowMatrix(Epetra_MpiComm(communicator))
    , K1(K1.trilinos_matrix())
    , K2(K2.trilinos_matrix())
    , K1_product(this->K1)
    , K2_product(this->K2)
    , n_local_1(this->K1.RowMap().NumMyElements())
  {
    const Epetra_Map rows  = owned.make_trilinos_map(communicator, false);
    const int        shift = static_cast<int>(offset);
    // Body 1's indices are below the offset: its rows come first.
    AssertThrow(rows.NumMyElements() ==
                  n_local_1 + this->K2.RowMap().NumMyElements(),
                ExcInternalError());

    std::vector<int> ghosts;
    append_ghost_columns(this->K1, 0, rows, ghosts);
    append_ghost_columns(this->K2, shift, rows, ghosts);
    for (const auto &[row, entries] : explicit_rows)
      for (const auto &entry : entries)
        if (!rows.MyGID(static_cast<int>(entry.first)))
          ghosts.push_back(static_cast<int>(entry.first));
    const Epetra_Map columns = column_map(rows, std::move(ghosts));
    SetMaps(rows, columns);
    columns_1 = combined_columns(this->K1, 0, columns);
    columns_2 = combined_columns(this->K2, shift, columns);

    explicit_start.push_back(0);
    for (const auto &[row, entries] : explicit_rows)
      {
        explicit_local_rows.push_back(rows.LID(static_cast<int>(row)));
        for (const auto &[column, value] : entries)
          {
            explicit_columns.push_back(columns.LID(static_cast<int>(column)));
            explicit_values.push_back(value);
          }
        explicit_start.push_back(explicit_columns.size());
      }
    Assert(std::is_sorted(explicit_local_rows.begin(),
                          explicit_local_rows.end()),
           ExcInternalError());
    // Epetra computes the global counts and norms when first asked, with
    // a reduction over the ranks; ML asks on each rank when that rank
    // needs a row, which the ranks need not do together. Computed here,
    // where every rank constructs the matrix.
    ComputeStructureConstants();
    ComputeNumericConstants();
  }



  int
  ReducedMatrix::explicit_index(const int row) const
  {
    const auto e = std::lower_bound(explicit_local_rows.begin(),
                                    explicit_local_rows.end(),
                                    row);
    if (e == explicit_local_rows.end() || *e != row)
      return -1;
    return e - explicit_local_rows.begin();
  }



  int
  ReducedMatrix::NumMyRowEntries(int row, int &n_entries) const
  {
    const int e = explicit_index(row);
    if (e >= 0)
      {
        n_entries = explicit_start[e + 1] - explicit_start[e];
        return 0;
      }
    const bool              first = row < n_local_1;
    int                     n;
    double                 *values;
    int                    *local_columns;
    const Epetra_CrsMatrix &K = first ? K1 : K2;
    K.ExtractMyRowView(first ? row : row - n_local_1, n, values, local_columns);
    n_entries =
      std::count_if(values, values + n, [](const double v) { return v != 0; });
    return 0;
  }



  // K's stored zeros are left out, as the explicit construction of A
  // (EliminatedOperator) leaves them out.
  int
  ReducedMatrix::ExtractMyRowCopy(int     row,
                                  int     length,
                                  int    &n_entries,
                                  double *values,
                                  int    *columns) const
  {
    if (row < 0 || row >= NumMyRows_)
      return -1;
    NumMyRowEntries(row, n_entries);
    if (n_entries > length)
      return -2;
    const int e = explicit_index(row);
    if (e >= 0)
      {
        std::copy(explicit_values.begin() + explicit_start[e],
                  explicit_values.begin() + explicit_start[e + 1],
                  values);
        std::copy(explicit_columns.begin() + explicit_start[e],
                  explicit_columns.begin() + explicit_start[e + 1],
                  columns);
        return 0;
      }
    const bool              first = row < n_local_1;
    const Epetra_CrsMatrix &K     = first ? K1 : K2;
    const std::vector<int> &local = first ? columns_1 : columns_2;
    int                     n;
    double                 *K_values;
    int                    *K_columns;
    K.ExtractMyRowView(first ? row : row - n_local_1, n, K_values, K_columns);
    int m = 0;
    for (int j = 0; j < n; ++j)
      if (K_values[j] != 0)
        {
          values[m]  = K_values[j];
          columns[m] = local[K_columns[j]];
          ++m;
        }
    return 0;
  }



  // Rows away from the interface: K's product (its stored zeros add
  // nothing); the explicit rows then replace theirs, summed in stored
  // order as Epetra sums a stored matrix's rows.
  int
  ReducedMatrix::Multiply(bool                      transpose,
                          const Epetra_MultiVector &X,
                          Epetra_MultiVector       &Y) const
  {
    if (transpose || X.NumVectors() != Y.NumVectors())
      return -1;
    const int n_vectors = X.NumVectors();
    // Y overwrites X's entries if they are the same vectors.
    std::unique_ptr<Epetra_MultiVector> X_copy;
    const Epetra_MultiVector           *x = &X;
    if (n_vectors > 0 && X[0] == Y[0])
      {
        X_copy = std::make_unique<Epetra_MultiVector>(X);
        x      = X_copy.get();
      }
    std::unique_ptr<Epetra_MultiVector> X_columns;
    if (Importer() != nullptr)
      {
        X_columns =
          std::make_unique<Epetra_MultiVector>(RowMatrixColMap(), n_vectors);
        X_columns->Import(*x, *Importer(), Insert);
      }

    for (int k = 0; k < n_vectors; ++k)
      {
        double       *x_k = (*x)[k];
        double       *y_k = Y[k];
        Epetra_Vector x1(View, K1.DomainMap(), x_k);
        Epetra_Vector x2(View, K2.DomainMap(), x_k + n_local_1);
        Epetra_Vector y1(View, K1.RangeMap(), y_k);
        Epetra_Vector y2(View, K2.RangeMap(), y_k + n_local_1);
        // ML calls this from its C code: errors as a return code, not as
        // an exception through its frames.
        try
          {
            K1_product.vmult(y1, x1);
            K2_product.vmult(y2, x2);
          }
        catch (...)
          {
            return -2;
          }

        const double *x_columns = X_columns ? (*X_columns)[k] : x_k;
        for (std::size_t e = 0; e < explicit_local_rows.size(); ++e)
          {
            double sum = 0.0;
            for (std::size_t j = explicit_start[e]; j < explicit_start[e + 1];
                 ++j)
              sum += explicit_values[j] * x_columns[explicit_columns[j]];
            y_k[explicit_local_rows[e]] = sum;
          }
      }
    return 0;
  }
} // namespace coulomb_adapt
