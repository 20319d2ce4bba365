#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_index_access.h>

#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>

#include <memory>

namespace coulomb_adapt
{
  namespace
  {
    // A's rows for every index of @p relevant: A itself on one rank, else
    // the owned rows imported onto an overlapping row map (what Ifpack's
    // overlapping Schwarz does internally).
    std::unique_ptr<Epetra_CrsMatrix>
    overlapping_rows(const TrilinosWrappers::SparseMatrix &A,
                     const IndexSet                       &relevant)
    {
      const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
      const Epetra_Map        map =
        relevant.make_trilinos_map(A.get_mpi_communicator(), true);
      Epetra_Import importer(map, matrix.RowMap());
      auto          rows = std::make_unique<Epetra_CrsMatrix>(Copy, map, 0);
      AssertThrow(rows->Import(matrix, importer, Insert) == 0,
                  ExcMessage("additive Schwarz: importing the patches' rows "
                             "failed"));
      rows->FillComplete(matrix.DomainMap(), matrix.RangeMap());
      return rows;
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



  } // namespace



  AdditiveSchwarzPreconditioner::AdditiveSchwarzPreconditioner(
    const TrilinosWrappers::SparseMatrix                    &A,
    const std::vector<std::vector<types::global_dof_index>> &patches,
    const IndexSet                                          &relevant_indices)
    : owned(A.locally_owned_range_indices())
    , relevant(relevant_indices)
    , communicator(A.get_mpi_communicator())
  {
    relevant.fill_index_vector(relevant_list);
    const auto       rows = overlapping_rows(A, relevant);
    std::vector<int> column_position(rows->ColMap().NumMyElements(), -1);
    std::size_t      total_size = 0;
    // Reserved: growing the vector would copy the factorised matrices,
    // and a copy forgets its factorisation.
    factors.reserve(patches.size());
    for (const auto &patch : patches)
      {
        // Drop the indices without an unknown (zero diagonal).
        const std::vector<double> full =
          dense_block(*rows, patch, column_position);
        std::vector<types::global_dof_index> kept;
        std::vector<std::size_t>             kept_at;
        for (std::size_t a = 0; a < patch.size(); ++a)
          if (full[a * patch.size() + a] != 0)
            {
              kept.push_back(patch[a]);
              kept_at.push_back(a);
            }
        if (kept.empty())
          continue;
        const std::size_t m = kept.size();
        // Factorised in place: a copy of a LAPACKFullMatrix forgets its
        // factorisation (its state starts again as a plain matrix).
        LAPACKFullMatrix<double> &block = factors.emplace_back(m, m);
        block.set_property(LAPACKSupport::symmetric);
        for (std::size_t a = 0; a < m; ++a)
          for (std::size_t b = 0; b < m; ++b)
            block(a, b) = full[kept_at[a] * patch.size() + kept_at[b]];
        block.compute_cholesky_factorization();
        std::vector<unsigned int> positions(m);
        for (std::size_t a = 0; a < m; ++a)
          positions[a] = relevant.index_within_set(kept[a]);
        patch_positions.push_back(std::move(positions));
        total_size += m;
      }
    n_global_patches =
      Utilities::MPI::sum(patch_positions.size(), communicator);
    mean_size =
      n_global_patches == 0 ?
        0. :
        Utilities::MPI::sum(static_cast<double>(total_size), communicator) /
          n_global_patches;
  }



  // The patches work on one array over the relevant indices: one
  // gather and one scatter per application instead of a map lookup per
  // patch entry.
  void
  AdditiveSchwarzPreconditioner::vmult(
    TrilinosWrappers::MPI::Vector       &dst,
    const TrilinosWrappers::MPI::Vector &src) const
  {
    TrilinosWrappers::MPI::Vector src_ghosted(owned, relevant, communicator);
    src_ghosted = src;
    std::vector<double> r(relevant_list.size()), z(relevant_list.size(), 0.);
    src_ghosted.extract_subvector_to(relevant_list, r);
    Vector<double> x;
    for (std::size_t p = 0; p < patch_positions.size(); ++p)
      {
        const auto &positions = patch_positions[p];
        x.reinit(positions.size(), true);
        for (std::size_t a = 0; a < positions.size(); ++a)
          x[a] = r[positions[a]];
        factors[p].solve(x);
        for (std::size_t a = 0; a < positions.size(); ++a)
          z[positions[a]] += x[a];
      }
    TrilinosWrappers::MPI::Vector sum;
    sum.reinit(owned, relevant, communicator, true);
    sum.add(relevant_list, z);
    sum.compress(VectorOperation::add);
    dst = sum;
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
