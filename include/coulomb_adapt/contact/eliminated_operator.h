#ifndef coulomb_adapt_contact_eliminated_operator_h
#define coulomb_adapt_contact_eliminated_operator_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/contact/reduced_matrix.h>

#include <array>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * A row of Z and Z~ that differs from the identity: an eliminated
   * component is a combination of other DoFs, with no entry of its own.
   * Per column the entries of Z and Z~, and the row's entry of u_g.
   */
  struct EliminatedRow
  {
    std::map<types::global_dof_index, std::array<double, 2>> entries;
    double                                                   shift = 0;
  };
  using EliminatedRows = std::map<types::global_dof_index, EliminatedRow>;

  /**
   * The products of the eliminated contact system (EliminatedContactSystem),
   *
   *   A = Z~^T K Z,   b = Z~^T (f - K u_g),   u = Z u~ + u_g,
   *
   * computed row by row from the bodies' K^1, K^2 and f^1, f^2, without a
   * combined copy of K, without Z as a matrix and without the
   * intermediate K Z. Z is the identity but for the rows of the
   * eliminated components (a few per active slave node), so a row i of
   * A is
   *
   *   (K Z)_i + sum_k Z~_ki (K Z)_k,   (K Z)_r = sum_l K_rl Z_l,
   *
   * the sum over the eliminated rows k that name i, and a row of K Z
   * differs from K's only where K has an eliminated column l. Away from
   * the contact interface a row of A is K's row, value for value. The
   * eliminated rows (and the K Z rows and residual entries at them) are
   * gathered on every rank: a row of A may need those of another rank,
   * and their number grows with the interface only.
   *
   * Z carries the placeholder on an eliminated component's diagonal
   * (EliminatedContactSystem::assemble), so that A has that row and
   * column in its pattern, and the values placeholder times K elsewhere
   * in them, as the matrix products computed them.
   */
  class EliminatedOperator
  {
  public:
    /** @p rows: the eliminated rows this rank owns; @p offset: the
     * shift of body 2's indices in the combined space. */
    EliminatedOperator(const TrilinosWrappers::SparseMatrix &K1,
                       const TrilinosWrappers::SparseMatrix &K2,
                       const TrilinosWrappers::MPI::Vector  &f1,
                       const TrilinosWrappers::MPI::Vector  &f2,
                       const types::global_dof_index         offset,
                       const IndexSet                       &owned,
                       const MPI_Comm                        communicator,
                       const EliminatedRows                 &rows,
                       const double                          placeholder);

    /** A in @p matrix (reinitialised), with the rows of the eliminated
     * components decoupled: K's diagonal entry only, the rest of their
     * pattern zero. */
    void
    reduced_matrix(TrilinosWrappers::SparseMatrix &matrix) const;

    /** The same A without a copy of K: its rows that differ from K's
     * stored, the others read from K^1, K^2 (ReducedMatrix), which must
     * outlive it. */
    std::shared_ptr<ReducedMatrix>
    reduced_operator() const;

    /** b in @p rhs (reinitialised), zero at the eliminated components. */
    void
    reduced_rhs(TrilinosWrappers::MPI::Vector &rhs) const;

    /** u = Z u~ + u_g for the eliminated rows @p rows this rank owns. */
    static void
    expand(const EliminatedRows                &rows,
           const double                         placeholder,
           const TrilinosWrappers::MPI::Vector &reduced_solution,
           TrilinosWrappers::MPI::Vector       &solution);

  private:
    using Entries = std::vector<std::pair<types::global_dof_index, double>>;

    /** All ranks' eliminated rows (this rank's are @p rows): all_rows,
     * is_eliminated and transposed. */
    void
    gather_eliminated_rows(const EliminatedRows &rows);
    /** All ranks' (K Z)_k and (f - K u_g)_k of the eliminated rows k
     * (this rank's are @p rows): eliminated_kz_rows. */
    void
    gather_kz_rows(const EliminatedRows &rows);
    /** f(column, value) for the entries of row @p row of K = diag(K^1,
     * K^2) in the combined index space (an owned row). */
    template <typename Function>
    void
    for_each_stiffness_entry(const types::global_dof_index row,
                             const Function               &f) const;
    /** The entries of row @p row of K Z, appended unsummed. */
    void
    append_kz_row(const types::global_dof_index row, Entries &entries) const;
    /** Row @p row of A (owned), summed, ascending columns. */
    void
    reduced_row(const types::global_dof_index row, Entries &entries) const;
    /** Row @p row of A as the matrix holds it: reduced_row(), or for an
     * eliminated component K's diagonal entry and zeros. */
    void
    matrix_row(const types::global_dof_index row, Entries &entries) const;
    /** Whether row @p row of A is not K's row. */
    bool
    differs_from_stiffness(const types::global_dof_index row) const;
    /** (f - K u_g)_r of an owned row. */
    double
    residual(const types::global_dof_index row) const;

    const TrilinosWrappers::SparseMatrix &K1;
    const TrilinosWrappers::SparseMatrix &K2;
    const TrilinosWrappers::MPI::Vector  &f1;
    const TrilinosWrappers::MPI::Vector  &f2;
    const types::global_dof_index         offset;
    const IndexSet                       &owned;
    const MPI_Comm                        communicator;
    const double                          placeholder;

    /** The eliminated rows of all ranks, and their membership by index. */
    EliminatedRows    all_rows;
    std::vector<bool> is_eliminated;
    /** For an owned column i of Z~: the eliminated rows k with a nonzero
     * Z~_ki, and Z~_ki. */
    std::unordered_map<types::global_dof_index,
                       std::vector<std::pair<types::global_dof_index, double>>>
      transposed;
    /** Of every eliminated row k (all ranks): (K Z)_k summed, and
     * (f - K u_g)_k. */
    std::map<types::global_dof_index, std::pair<Entries, double>>
      eliminated_kz_rows;
  };
} // namespace coulomb_adapt

#endif
