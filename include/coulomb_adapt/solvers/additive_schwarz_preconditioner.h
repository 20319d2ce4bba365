#ifndef coulomb_adapt_solvers_additive_schwarz_preconditioner_h
#define coulomb_adapt_solvers_additive_schwarz_preconditioner_h

#include <deal.II/base/index_set.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>

#include <memory>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * One-level additive Schwarz preconditioner with exact dense solves on
   * overlapping patches of unknowns:
   *   P^-1 r = sum_patches R_p^T A_pp^-1 R_p r,
   * A_pp the rows and columns of A named by the patch (taken from A
   * itself, also the rows another rank owns). The patches are given as
   * global indices, each by one rank (e.g. the unknowns of the cells
   * around a vertex that rank owns); every unknown with a nonzero
   * diagonal must be in some patch. Unknowns whose diagonal is zero are
   * dropped from the patches and get zero.
   *
   * Why not Trilinos' Ifpack or ML: their blocks and overlap follow the
   * parallel partition, so the preconditioned iterates, and anything
   * computed from a truncated iteration, would change with the number of
   * ranks; here the patches follow the mesh, and only the summation order
   * of the overlapping corrections does.
   *
   * Each A_pp^-1 is kept explicitly (LAPACK's Cholesky factor and inverse,
   * once) and applied as a dense product: the patches are small (~20 on
   * the estimator's vertex patches), where a LAPACK call per patch and
   * application (two triangular solves) cost more in call overhead than
   * in flops, while the product is the same 2 m^2 flops in one loop the
   * compiler vectorises.
   */
  class AdditiveSchwarzPreconditioner
  {
  public:
    /**
     * @p A: the matrix (owned rows); @p relevant: every index of the
     * patches given on this rank (a superset of A's owned rows there).
     */
    AdditiveSchwarzPreconditioner(
      const TrilinosWrappers::SparseMatrix                    &A,
      const std::vector<std::vector<types::global_dof_index>> &patches,
      const IndexSet                                          &relevant);

    /**
     * Not thread-safe: it works in the preconditioner's own ghosted
     * vectors.
     */
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

    /**
     * The number of patches and their mean size, summed over the ranks.
     */
    std::size_t
    n_patches() const;

    double
    mean_patch_size() const;

  private:
    // The relevant indices' values: imported from the owned ones before
    // the patches are applied, their sums exported (added) after.
    std::unique_ptr<Epetra_Map>            relevant_map;
    std::unique_ptr<Epetra_Import>         owned_to_relevant;
    mutable std::unique_ptr<Epetra_Vector> r_relevant, z_relevant;
    // Patch p: its (nonzero-diagonal) indices' positions within the
    // relevant ones, positions[starts[p] .. starts[p + 1]), and A_pp^-1
    // by columns from inverses[inverse_starts[p]].
    std::vector<unsigned int> positions;
    std::vector<std::size_t>  starts, inverse_starts;
    std::vector<double>       inverses;
    // Scratch of vmult(): each patch's correction, at its positions.
    mutable std::vector<double> corrections;
    std::size_t                 n_global_patches = 0;
    double                      mean_size        = 0;
  };
} // namespace coulomb_adapt

#endif
