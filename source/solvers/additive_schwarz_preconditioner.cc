#include <deal.II/base/mpi.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>

#include <algorithm>

namespace coulomb_adapt
{
  namespace
  {
    // A's rows for every index of @p relevant: A itself when every rank's
    // relevant rows are its own (one rank), else the owned rows imported
    // onto an overlapping row map (what Ifpack's overlapping Schwarz does
    // internally). @p imported keeps the import alive.
    const Epetra_CrsMatrix &
    overlapping_rows(const TrilinosWrappers::SparseMatrix &A,
                     const IndexSet                       &relevant,
                     std::unique_ptr<Epetra_CrsMatrix>    &imported)
    {
      const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
      const MPI_Comm          comm   = A.get_mpi_communicator();
      const bool              own_rows_only =
        Utilities::MPI::min(static_cast<unsigned int>(
                              relevant == A.locally_owned_range_indices()),
                            comm) == 1;
      if (own_rows_only)
        return matrix;
      const Epetra_Map map = relevant.make_trilinos_map(comm, true);
      Epetra_Import    importer(map, matrix.RowMap());
      imported = std::make_unique<Epetra_CrsMatrix>(Copy, map, 0);
      AssertThrow(imported->Import(matrix, importer, Insert) == 0,
                  ExcMessage("additive Schwarz: importing the patches' rows "
                             "failed"));
      imported->FillComplete(matrix.DomainMap(), matrix.RangeMap());
      return *imported;
    }



    // The block of @p rows named by @p indices (sorted), dense by rows;
    // column_position maps a column LID of @p rows to its place in the
    // patch (-1 elsewhere) and is left as it was found.
    std::vector<double>
    dense_block(const Epetra_CrsMatrix                     &rows,
                const std::vector<types::global_dof_index> &indices,
                std::vector<int>                           &column_position)
    {
      const std::size_t m = indices.size();
      for (std::size_t a = 0; a < m; ++a)
        column_position[rows.ColMap().LID(
          static_cast<TrilinosWrappers::types::int_type>(indices[a]))] =
          static_cast<int>(a);
      std::vector<double> block(m * m, 0.);
      for (std::size_t a = 0; a < m; ++a)
        {
          int     n_entries;
          double *values;
          int    *columns;
          rows.ExtractMyRowView(
            rows.RowMap().LID(
              static_cast<TrilinosWrappers::types::int_type>(indices[a])),
            n_entries,
            values,
            columns);
          for (int e = 0; e < n_entries; ++e)
            if (const int b = column_position[columns[e]]; b >= 0)
              block[a * m + b] = values[e];
        }
      for (const auto i : indices)
        column_position[rows.ColMap().LID(
          static_cast<TrilinosWrappers::types::int_type>(i))] = -1;
      return block;
    }



    // z += A_pp^-1 r on one patch: the gathered r, the product by the
    // columns of A_pp^-1 (independent multiply-adds along a contiguous
    // column, which vectorise, instead of a chain of dot products per
    // row), scattered back.
    void
    add_patch_correction(const unsigned int *const positions,
                         const std::size_t         m,
                         const double *const       inverse,
                         const double *const       r,
                         double *const             z,
                         double *const __restrict  gathered,
                         double *const __restrict  product)
    {
      for (std::size_t a = 0; a < m; ++a)
        gathered[a] = r[positions[a]];
      std::fill(product, product + m, 0.);
      for (std::size_t b = 0; b < m; ++b)
        {
          const double        r_b    = gathered[b];
          const double *const column = inverse + b * m;
          for (std::size_t a = 0; a < m; ++a)
            product[a] += column[a] * r_b;
        }
      for (std::size_t a = 0; a < m; ++a)
        z[positions[a]] += product[a];
    }
  } // namespace



  AdditiveSchwarzPreconditioner::AdditiveSchwarzPreconditioner(
    const TrilinosWrappers::SparseMatrix                    &A,
    const std::vector<std::vector<types::global_dof_index>> &patches,
    const IndexSet                                          &relevant)
  {
    const MPI_Comm comm = A.get_mpi_communicator();
    relevant_map =
      std::make_unique<Epetra_Map>(relevant.make_trilinos_map(comm, true));
    owned_to_relevant =
      std::make_unique<Epetra_Import>(*relevant_map,
                                      A.trilinos_matrix().RangeMap());
    r_relevant = std::make_unique<Epetra_Vector>(*relevant_map);
    z_relevant = std::make_unique<Epetra_Vector>(*relevant_map);

    std::unique_ptr<Epetra_CrsMatrix> imported;
    const Epetra_CrsMatrix &rows = overlapping_rows(A, relevant, imported);
    std::vector<int>        column_position(rows.ColMap().NumMyElements(), -1);
    starts.push_back(0);
    inverse_starts.push_back(0);
    LAPACKFullMatrix<double> block;
    for (const auto &patch : patches)
      {
        // Drop the indices without an unknown (zero diagonal).
        const std::vector<double> full =
          dense_block(rows, patch, column_position);
        std::vector<std::size_t> kept_at;
        for (std::size_t a = 0; a < patch.size(); ++a)
          if (full[a * patch.size() + a] != 0)
            kept_at.push_back(a);
        if (kept_at.empty())
          continue;
        const std::size_t m = kept_at.size();
        block.reinit(m, m);
        block.set_property(LAPACKSupport::symmetric);
        for (std::size_t a = 0; a < m; ++a)
          for (std::size_t b = 0; b < m; ++b)
            block(a, b) = full[kept_at[a] * patch.size() + kept_at[b]];
        // LAPACK's Cholesky factor and inverse (potrf, potri; deal.II
        // copies the lower triangle up, so it is exactly symmetric and its
        // rows are its columns).
        block.invert();
        for (std::size_t b = 0; b < m; ++b)
          for (std::size_t a = 0; a < m; ++a)
            inverses.push_back(block(a, b));
        for (const std::size_t a : kept_at)
          positions.push_back(relevant.index_within_set(patch[a]));
        starts.push_back(positions.size());
        inverse_starts.push_back(inverses.size());
      }
    const std::size_t n_local_patches = starts.size() - 1;
    n_global_patches = Utilities::MPI::sum(n_local_patches, comm);
    mean_size =
      n_global_patches == 0 ?
        0. :
        Utilities::MPI::sum(static_cast<double>(positions.size()), comm) /
          n_global_patches;
  }



  // The patches work on the relevant indices' values, positions being
  // their local indices there (make_trilinos_map keeps the index set's
  // order): one import and one export per application, with the
  // communication pattern built once.
  void
  AdditiveSchwarzPreconditioner::vmult(
    TrilinosWrappers::MPI::Vector       &dst,
    const TrilinosWrappers::MPI::Vector &src) const
  {
    AssertThrow(r_relevant->Import(src.trilinos_vector(),
                                   *owned_to_relevant,
                                   Insert) == 0,
                ExcMessage("additive Schwarz: importing the residual failed"));
    z_relevant->PutScalar(0.);
    const double *const r = r_relevant->Values();
    double *const       z = z_relevant->Values();
    std::vector<double> gathered, product;
    for (std::size_t p = 0; p + 1 < starts.size(); ++p)
      {
        const std::size_t m = starts[p + 1] - starts[p];
        gathered.resize(m);
        product.resize(m);
        add_patch_correction(&positions[starts[p]],
                             m,
                             &inverses[inverse_starts[p]],
                             r,
                             z,
                             gathered.data(),
                             product.data());
      }
    // Each owned index is one relevant index of its own rank: the export
    // copies that one and adds the other ranks' ones.
    dst = 0;
    AssertThrow(dst.trilinos_vector().Export(*z_relevant,
                                             *owned_to_relevant,
                                             Add) == 0,
                ExcMessage("additive Schwarz: exporting the corrections "
                           "failed"));
  }



  std::size_t
  AdditiveSchwarzPreconditioner::n_patches() const
  {
    return n_global_patches;
  }



  double
  AdditiveSchwarzPreconditioner::mean_patch_size() const
  {
    return mean_size;
  }
} // namespace coulomb_adapt
