#ifndef coulomb_adapt_indicator_element_mass_operator_h
#define coulomb_adapt_indicator_element_mass_operator_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/subscriptor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_block_vector.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <coulomb_adapt/indicator/quadrature_stress.h>

#include <memory>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The mass matrix of a body's scalar continuous space (the ZZ projection's
   * system), kept element by element: one dense matrix per locally owned
   * cell, applied by a loop over the cells.
   *
   * Why not an assembled sparse matrix: on meshes of 10^3 DoFs, building
   * its sparsity pattern and the Epetra graph and matrix cost more than the
   * CG solve itself, and an adaptive run builds them again on every mesh.
   * The element matrices come from the weights JxW that QuadratureStress
   * already holds and the reference shape values, so setting this operator
   * up is one short pass over the cells.
   *
   * Hanging nodes are treated as deal.II's matrix-free operators treat them
   * (step-37): on the unconstrained DoFs the operator is C^T M C, on the
   * constrained ones the identity, so CG started from zero keeps the
   * constrained entries zero; AffineConstraints::distribute fills them in
   * afterwards.
   *
   * The operator acts on each of the three blocks of a block vector, the
   * three stress components: they are solved for in one CG on the
   * block-diagonal system diag(M, M, M). It has the spectrum of M, so CG
   * needs the steps of one component, and each step reads the element
   * matrices and indices once for all three instead of once per component.
   */
  class ElementMassOperator : public Subscriptor
  {
  public:
    using VectorType      = LinearAlgebra::distributed::Vector<double>;
    using BlockVectorType = LinearAlgebra::distributed::BlockVector<double>;

    /** Blocks of the vectors that vmult() acts on (xx, yy, xy). */
    static constexpr unsigned int n_blocks = 3;

    /** Nodes per cell of a Q3 element: more than the degrees the program
     * offers (1 and 2). Local vectors of this size live on the stack. */
    static constexpr unsigned int max_dofs_per_cell = 16;

    /**
     * Set up on @p dofs (a scalar space on the body of @p weights, with the
     * hanging-node @p constraints), whose vectors have the owned and ghost
     * entries of @p partitioner (the locally relevant DoFs). @p shape_values
     * holds phi_k at the points of the body's cell quadrature (k, q). Keeps
     * a reference to @p constraints, which must be homogeneous (hanging
     * nodes): the operator is linear only then.
     */
    ElementMassOperator(
      const DoFHandler<2>                                      &dofs,
      const AffineConstraints<double>                          &constraints,
      const std::shared_ptr<const Utilities::MPI::Partitioner> &partitioner,
      const FullMatrix<double>                                 &shape_values,
      const QuadratureStress                                   &weights);

    /** A vector with the locally owned and ghost entries of this space. */
    void
    initialize_dof_vector(VectorType &vector) const;

    /** n_blocks such vectors. */
    void
    initialize_dof_vector(BlockVectorType &vector) const;

    /** dst = A src, block by block. */
    void
    vmult(BlockVectorType &dst, const BlockVectorType &src) const;

    /** dst = omega D^-1 src, block by block, with D the diagonal of the
     * operator: for deal.II's PreconditionJacobi. */
    void
    precondition_Jacobi(BlockVectorType       &dst,
                        const BlockVectorType &src,
                        const double           omega) const;

    /**
     * Add @p cell_vector, the values of a cell integral for the DoFs of
     * owned cell number @p cell (numbered as in QuadratureStress), to
     * @p dst through the hanging-node constraints. Call
     * dst.compress(VectorOperation::add) after the last cell.
     */
    void
    distribute_local_to_global(const unsigned int             cell,
                               const ArrayView<const double> &cell_vector,
                               VectorType                    &dst) const;

  private:
    void
    compute_inverse_diagonal();

    /** The cell loop of vmult() for @p n_static nodes per cell (0: as
     * many as the element has, not known at compile time). */
    template <unsigned int n_static>
    void
    apply_element_matrices(BlockVectorType       &dst,
                           const BlockVectorType &src) const;

    const AffineConstraints<double>                   &constraints;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    unsigned int                                       n_dofs_per_cell;
    /** Per owned cell, n_dofs_per_cell entries each: the DoFs as indices
     * into the local (owned, then ghost) entries of a VectorType, and as
     * global indices for AffineConstraints. */
    std::vector<unsigned int>            local_indices;
    std::vector<types::global_dof_index> global_indices;
    /** Whether an owned cell has a constrained DoF (hanging node); bytes,
     * not std::vector<bool>, which is read once per cell and CG step. */
    std::vector<unsigned char> cell_is_constrained;
    /** Owned constrained DoFs, as local indices. */
    std::vector<unsigned int> constrained_local_dofs;
    /** Per owned cell, the element matrix, row by row. */
    std::vector<double> cell_matrices;
    VectorType          diagonal_inverse;
  };
} // namespace coulomb_adapt

#endif
