#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/thread_local_storage.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>

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



    // A_pp^-1 r on one patch into @p product: the gathered r, the product
    // by the columns of A_pp^-1 (independent multiply-adds along a
    // contiguous column, which vectorise, instead of a chain of dot
    // products per row).
    void
    patch_correction(const unsigned int *const positions,
                     const std::size_t         m,
                     const double *const       inverse,
                     const double *const       r,
                     double *const __restrict gathered,
                     double *const __restrict product)
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
    }



    // The diagonal of @p rows, by local row.
    std::vector<double>
    row_diagonal(const Epetra_CrsMatrix &rows)
    {
      Epetra_Vector diagonal(rows.RowMap());
      AssertThrow(rows.ExtractDiagonalCopy(diagonal) == 0,
                  ExcMessage("additive Schwarz: extracting the diagonal "
                             "failed"));
      return std::vector<double>(diagonal.Values(),
                                 diagonal.Values() + diagonal.MyLength());
    }



    // The places in @p patch of its unknowns: the indices with a nonzero
    // diagonal (@p diagonal: that of @p rows).
    std::vector<std::size_t>
    kept_unknowns(const std::vector<types::global_dof_index> &patch,
                  const Epetra_CrsMatrix                     &rows,
                  const std::vector<double>                  &diagonal)
    {
      std::vector<std::size_t> kept_at;
      for (std::size_t a = 0; a < patch.size(); ++a)
        if (diagonal[rows.RowMap().LID(
              static_cast<TrilinosWrappers::types::int_type>(patch[a]))] != 0)
          kept_at.push_back(a);
      return kept_at;
    }



    // The inverse of the block of @p patch's unknowns @p kept_at, by
    // columns, into @p inverse (m^2 entries), and their local indices
    // among the relevant ones into @p positions (m entries).
    void
    invert_patch(const Epetra_CrsMatrix                     &rows,
                 const std::vector<types::global_dof_index> &patch,
                 const std::vector<std::size_t>             &kept_at,
                 const IndexSet                             &relevant,
                 std::vector<int>                           &column_position,
                 LAPACKFullMatrix<double>                   &block,
                 unsigned int *const                         positions,
                 double *const                               inverse)
    {
      const std::vector<double> full =
        dense_block(rows, patch, column_position);
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
          inverse[b * m + a] = block(a, b);
      for (std::size_t a = 0; a < m; ++a)
        positions[a] = relevant.index_within_set(patch[kept_at[a]]);
    }



    // Patches per task of the threaded loops: a patch is ~2 m^2 = 800
    // flops on the estimator's vertex patches.
    constexpr unsigned int patches_per_task = 256;
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
    // Each patch's unknowns (the indices with a nonzero diagonal) give it
    // its place in the arrays; then the patches are inverted independently
    // on the threads deal.II may use (each thread with its own column
    // map), into those places. The same preconditioner on any number of
    // threads.
    const std::vector<double>             diagonal = row_diagonal(rows);
    std::vector<std::vector<std::size_t>> kept(patches.size());
    for (std::size_t p = 0; p < patches.size(); ++p)
      kept[p] = kept_unknowns(patches[p], rows, diagonal);
    Threads::ThreadLocalStorage<std::vector<int>> column_positions(
      std::vector<int>(rows.ColMap().NumMyElements(), -1));
    std::vector<std::size_t> kept_patches;
    starts.push_back(0);
    inverse_starts.push_back(0);
    for (std::size_t p = 0; p < patches.size(); ++p)
      if (const std::size_t m = kept[p].size(); m > 0)
        {
          kept_patches.push_back(p);
          starts.push_back(starts.back() + m);
          inverse_starts.push_back(inverse_starts.back() + m * m);
        }
    positions.resize(starts.back());
    inverses.resize(inverse_starts.back());
    Threads::ThreadLocalStorage<LAPACKFullMatrix<double>> blocks;
    parallel::apply_to_subranges(
      std::size_t(0),
      kept_patches.size(),
      [&](const std::size_t begin, const std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
          {
            const std::size_t p = kept_patches[k];
            invert_patch(rows,
                         patches[p],
                         kept[p],
                         relevant,
                         column_positions.get(),
                         blocks.get(),
                         &positions[starts[k]],
                         &inverses[inverse_starts[k]]);
          }
      },
      patches_per_task);
    corrections.resize(positions.size());
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
    // The patches' corrections on the threads, each into its own slice of
    // corrections; then added up in the patches' order, so that z does not
    // depend on the number of threads.
    parallel::apply_to_subranges(
      std::size_t(0),
      starts.size() - 1,
      [&](const std::size_t begin, const std::size_t end) {
        std::vector<double> gathered;
        for (std::size_t p = begin; p < end; ++p)
          {
            const std::size_t m = starts[p + 1] - starts[p];
            gathered.resize(m);
            patch_correction(&positions[starts[p]],
                             m,
                             &inverses[inverse_starts[p]],
                             r,
                             gathered.data(),
                             &corrections[starts[p]]);
          }
      },
      patches_per_task);
    for (std::size_t i = 0; i < positions.size(); ++i)
      z[positions[i]] += corrections[i];
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
