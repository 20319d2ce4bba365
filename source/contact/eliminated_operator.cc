#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <coulomb_adapt/contact/eliminated_operator.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <algorithm>

namespace coulomb_adapt
{
  namespace
  {
    using Entries = std::vector<std::pair<types::global_dof_index, double>>;

    // Ascending columns, the values of a column summed in the order they
    // were appended.
    void
    sum_duplicates(Entries &entries)
    {
      const auto by_column = [](const auto &a, const auto &b) {
        return a.first < b.first;
      };
      // Most rows are K's, ascending already.
      if (std::is_sorted(entries.begin(), entries.end(), by_column))
        {
          if (std::adjacent_find(entries.begin(),
                                 entries.end(),
                                 [](const auto &a, const auto &b) {
                                   return a.first == b.first;
                                 }) == entries.end())
            return;
        }
      else
        std::stable_sort(entries.begin(), entries.end(), by_column);
      std::size_t n = 0;
      for (std::size_t e = 0; e < entries.size(); ++e)
        if (n > 0 && entries[n - 1].first == entries[e].first)
          entries[n - 1].second += entries[e].second;
        else
          entries[n++] = entries[e];
      entries.resize(n);
    }

    // Rows packed as indices [row, n, columns...] and values [scalar,
    // n values...] (or [scalar, 2 n values...]), gathered from all ranks,
    // and unpacked by f(row, columns, values, scalar).
    template <typename Function>
    void
    for_each_gathered_row(const MPI_Comm communicator,
                          const std::vector<types::global_dof_index> &indices,
                          const std::vector<double>                  &values,
                          const unsigned int values_per_column,
                          const Function    &f)
    {
      const auto all_indices =
        Utilities::MPI::all_gather(communicator, indices);
      const auto all_values = Utilities::MPI::all_gather(communicator, values);
      for (unsigned int p = 0; p < all_indices.size(); ++p)
        {
          const auto &index = all_indices[p];
          const auto &value = all_values[p];
          std::size_t i = 0, v = 0;
          while (i < index.size())
            {
              const types::global_dof_index row = index[i];
              const std::size_t             n   = index[i + 1];
              f(row, &index[i + 2], n, &value[v + 1], value[v]);
              i += 2 + n;
              v += 1 + values_per_column * n;
            }
        }
    }
  } // namespace



  EliminatedOperator::EliminatedOperator(
    const TrilinosWrappers::SparseMatrix &K1,
    const TrilinosWrappers::SparseMatrix &K2,
    const TrilinosWrappers::MPI::Vector  &f1,
    const TrilinosWrappers::MPI::Vector  &f2,
    const types::global_dof_index         offset,
    const IndexSet                       &owned,
    const MPI_Comm                        communicator,
    const EliminatedRows                 &rows,
    const double                          placeholder)
    : K1(K1)
    , K2(K2)
    , f1(f1)
    , f2(f2)
    , offset(offset)
    , owned(owned)
    , communicator(communicator)
    , placeholder(placeholder)
    , is_eliminated(owned.size(), false)
  {
    gather_eliminated_rows(rows);
    gather_kz_rows(rows);
  }



  // Every rank's eliminated rows in all_rows, their membership in
  // is_eliminated, and Z~ transposed at the owned columns.
  void
  EliminatedOperator::gather_eliminated_rows(const EliminatedRows &rows)
  {
    std::vector<types::global_dof_index> indices;
    std::vector<double>                  values;
    for (const auto &[k, row] : rows)
      {
        indices.push_back(k);
        indices.push_back(row.entries.size());
        values.push_back(row.shift);
        for (const auto &[column, z] : row.entries)
          {
            indices.push_back(column);
            values.push_back(z[0]);
            values.push_back(z[1]);
          }
      }
    for_each_gathered_row(
      communicator,
      indices,
      values,
      2,
      [&](const types::global_dof_index  k,
          const types::global_dof_index *columns,
          const std::size_t              n,
          const double                  *z,
          const double                   shift) {
        EliminatedRow &row = all_rows[k];
        row.shift          = shift;
        for (std::size_t e = 0; e < n; ++e)
          row.entries[columns[e]] = {{z[2 * e], z[2 * e + 1]}};
      });
    // An explicit zero of Z~ (a master DoF with Dirichlet data) adds
    // nothing, and the transposed product did not keep it either.
    for (const auto &[k, row] : all_rows)
      {
        is_eliminated[k] = true;
        for (const auto &[column, z] : row.entries)
          if (z[1] != 0 && owned.is_element(column))
            transposed[column].emplace_back(k, z[1]);
      }
  }



  // The rows of K Z and the residual at the eliminated components,
  // which other ranks' rows of A and b may name.
  void
  EliminatedOperator::gather_kz_rows(const EliminatedRows &rows)
  {
    std::vector<types::global_dof_index> indices;
    std::vector<double>                  values;
    Entries                              entries;
    for (const auto &[k, row] : rows)
      {
        entries.clear();
        append_kz_row(k, entries);
        sum_duplicates(entries);
        indices.push_back(k);
        indices.push_back(entries.size());
        values.push_back(residual(k));
        for (const auto &[column, value] : entries)
          {
            indices.push_back(column);
            values.push_back(value);
          }
      }
    for_each_gathered_row(communicator,
                          indices,
                          values,
                          1,
                          [&](const types::global_dof_index  k,
                              const types::global_dof_index *columns,
                              const std::size_t              n,
                              const double                  *kz,
                              const double                   r) {
                            auto &row = eliminated_kz_rows[k];
                            for (std::size_t e = 0; e < n; ++e)
                              row.first.emplace_back(columns[e], kz[e]);
                            row.second = r;
                          });
  }



  template <typename Function>
  void
  EliminatedOperator::for_each_stiffness_entry(
    const types::global_dof_index row,
    const Function               &f) const
  {
    if (row < offset)
      for_each_entry(K1, row, f);
    else
      for_each_entry(K2,
                     row - offset,
                     [&](const types::global_dof_index column,
                         const double value) { f(offset + column, value); });
  }



  // (K Z)_r = sum_l K_rl Z_l: Z_l is the unit row where l is not
  // eliminated (the entry is K's, exactly), otherwise the placeholder on
  // the diagonal and the eliminated row's entries. Stored zeros of K are
  // left out, as the products left them out (zeros of Z are kept: so did
  // they).
  void
  EliminatedOperator::append_kz_row(const types::global_dof_index row,
                                    Entries                      &entries) const
  {
    for_each_stiffness_entry(
      row, [&](const types::global_dof_index l, const double K_rl) {
        if (K_rl == 0)
          return;
        if (!is_eliminated[l])
          {
            entries.emplace_back(l, K_rl);
            return;
          }
        entries.emplace_back(l, K_rl * placeholder);
        for (const auto &[column, z] : all_rows.find(l)->second.entries)
          entries.emplace_back(column, K_rl * z[0]);
      });
  }



  // A_i = Z~_ii (K Z)_i + sum_k Z~_ki (K Z)_k. Z~_ii is 1 where i is not
  // eliminated; the rows of eliminated components are replaced anyway.
  // The terms are summed by increasing k (i among them), as the matrix
  // products (Trilinos' transpose, then ML) summed them on one rank: A is
  // the same to the last bit there. On several ranks the products took
  // other ranks' terms in another order, which changes the last bit of a
  // few entries near the interface.
  void
  EliminatedOperator::reduced_row(const types::global_dof_index row,
                                  Entries                      &entries) const
  {
    entries.clear();
    append_kz_row(row, entries);
    sum_duplicates(entries);
    const auto terms = transposed.find(row);
    if (terms == transposed.end())
      return;
    Entries own_row;
    std::swap(own_row, entries);
    bool own_row_added = false;
    for (const auto &[k, z_test] : terms->second)
      {
        if (!own_row_added && row < k)
          {
            entries.insert(entries.end(), own_row.begin(), own_row.end());
            own_row_added = true;
          }
        for (const auto &[column, value] : eliminated_kz_rows.at(k).first)
          entries.emplace_back(column, z_test * value);
      }
    if (!own_row_added)
      entries.insert(entries.end(), own_row.begin(), own_row.end());
    sum_duplicates(entries);
  }



  double
  EliminatedOperator::residual(const types::global_dof_index row) const
  {
    double Ku = 0;
    for_each_stiffness_entry(row,
                             [&](const types::global_dof_index l,
                                 const double                  K_rl) {
                               if (is_eliminated[l])
                                 Ku += K_rl * all_rows.find(l)->second.shift;
                             });
    const double f = row < offset ? f1(row) : f2(row - offset);
    return f - Ku;
  }



  // An eliminated component's row is decoupled: K's diagonal entry, so
  // that the operator keeps the scale AMG's smoother expects, and zeros
  // in the rest of its pattern.
  void
  EliminatedOperator::matrix_row(const types::global_dof_index row,
                                 Entries                      &entries) const
  {
    reduced_row(row, entries);
    if (!is_eliminated[row])
      return;
    double diagonal = 0;
    for_each_stiffness_entry(row,
                             [&](const types::global_dof_index l,
                                 const double                  K_il) {
                               if (l == row)
                                 diagonal = K_il;
                             });
    bool has_diagonal = false;
    for (auto &[column, value] : entries)
      {
        value        = column == row ? diagonal : 0.;
        has_diagonal = has_diagonal || column == row;
      }
    Assert(has_diagonal, ExcInternalError());
    (void)has_diagonal;
  }



  // A row of A is K's (its stored zeros left out) unless the row is
  // eliminated, names an eliminated column with a nonzero of K, or is
  // named by an eliminated row of Z~.
  bool
  EliminatedOperator::differs_from_stiffness(
    const types::global_dof_index row) const
  {
    if (is_eliminated[row] || transposed.count(row) > 0)
      return true;
    bool differs = false;
    for_each_stiffness_entry(
      row, [&](const types::global_dof_index l, const double K_rl) {
        differs = differs || (K_rl != 0 && is_eliminated[l]);
      });
    return differs;
  }



  // Two passes over the rows, the pattern and then the values: the
  // pattern's transient is that of one matrix's indices, where the
  // products held K Z and three copies of the result at once.
  void
  EliminatedOperator::reduced_matrix(
    TrilinosWrappers::SparseMatrix &matrix) const
  {
    Entries                              entries;
    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    {
      DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
      for (const auto i : owned)
        {
          reduced_row(i, entries);
          columns.clear();
          for (const auto &entry : entries)
            columns.push_back(entry.first);
          dsp.add_entries(i, columns.begin(), columns.end(), true);
        }
      matrix.reinit(owned, owned, dsp, communicator);
    }

    for (const auto i : owned)
      {
        matrix_row(i, entries);
        columns.clear();
        values.clear();
        for (const auto &[column, value] : entries)
          {
            columns.push_back(column);
            values.push_back(value);
          }
        matrix.set(i, columns.size(), columns.data(), values.data());
      }
    matrix.compress(VectorOperation::insert);
  }



  std::shared_ptr<ReducedMatrix>
  EliminatedOperator::reduced_operator() const
  {
    ReducedMatrix::Rows rows;
    for (const auto i : owned)
      if (differs_from_stiffness(i))
        matrix_row(i, rows[i]);
    return std::make_shared<ReducedMatrix>(
      K1, K2, offset, owned, communicator, rows);
  }



  // b_i = (f - K u_g)_i + sum_k Z~_ki (f - K u_g)_k.
  void
  EliminatedOperator::reduced_rhs(TrilinosWrappers::MPI::Vector &rhs) const
  {
    rhs.reinit(owned, communicator);
    for (const auto i : owned)
      {
        if (is_eliminated[i])
          continue;
        double     b     = residual(i);
        const auto terms = transposed.find(i);
        if (terms != transposed.end())
          for (const auto &[k, z_test] : terms->second)
            b += z_test * eliminated_kz_rows.at(k).second;
        rhs(i) = b;
      }
    rhs.compress(VectorOperation::insert);
  }



  // u = u~ where nothing is eliminated; an eliminated row needs the
  // entries of u~ that it names, owned by any rank.
  void
  EliminatedOperator::expand(
    const EliminatedRows                &rows,
    const double                         placeholder,
    const TrilinosWrappers::MPI::Vector &reduced_solution,
    TrilinosWrappers::MPI::Vector       &solution)
  {
    const IndexSet owned    = reduced_solution.locally_owned_elements();
    IndexSet       relevant = owned;
    for (const auto &[k, row] : rows)
      for (const auto &[column, z] : row.entries)
        relevant.add_index(column);
    relevant.compress();
    TrilinosWrappers::MPI::Vector ghosted(
      owned, relevant, reduced_solution.get_mpi_communicator());
    ghosted = reduced_solution;

    solution.reinit(owned, reduced_solution.get_mpi_communicator());
    solution = reduced_solution;
    for (const auto &[k, row] : rows)
      {
        double u = placeholder * ghosted(k);
        for (const auto &[column, z] : row.entries)
          u += z[0] * ghosted(column);
        solution(k) = u + row.shift;
      }
    solution.compress(VectorOperation::insert);
  }
} // namespace coulomb_adapt
