#ifndef coulomb_adapt_contact_row_replacing_contact_system_h
#define coulomb_adapt_contact_row_replacing_contact_system_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/contact/condensed_newton_system.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * The condensed Newton system for direct solvers: the rows of body 1's
   * slave DoFs are replaced by the conditions of the node's set, and the
   * master rows receive the condensed contact force
   * M^T lambda = M^T D^-1 (f^1 - K^1 u^1). The matrix is not symmetric.
   *
   *   open node:   both rows  e_c . (K^1 u^1)_j = e_c . f^1_j
   *                           (lambda_j = 0),
   *   active node: normal row n . (D u^1 - M u^2)_j = g~_j, scaled like a
   *                           row of K^1,
   *   stick node:  tangent row t . (D u^1 - M u^2)_j = the weighted slip of
   *                           the previous load step,
   *   slip node:   tangent row (t - mu s n) . (K^1 u^1)_j = (...) . f^1_j
   *                           (lambda_t = mu s lambda_n),
   *   roller node: the fixed component's row stays K^1's (its Dirichlet
   *                           condition); the free component's row is the
   *                           normal row (active) or its traction row
   *                           (open: lambda_n = 0), whatever the set says
   *                           tangentially.
   *
   * The normal condition goes into the row of the displacement component
   * most aligned with n, so that it has a large diagonal entry.
   */
  class RowReplacingContactSystem : public CondensedNewtonSystem
  {
  public:
    /** The sparsity pattern, which does not depend on the sets. */
    void
    reinit(const MortarInterface   &mortar,
           const ElasticBody       &slave,
           const ElasticBody       &master,
           const SlaveCondensation &condensation) override;

    void
    assemble(const std::vector<SlaveNodeConditions> &nodes) override;

    LinearSolverReport
    solve(const std::vector<std::vector<double>> &near_null_space,
          const parameters::LinearSolver         &settings,
          TrilinosWrappers::MPI::Vector          &solution) override;

  private:
    /** Body 1's rows away from the slave nodes, and body 2's rows with
     * the condensed contact force in the master rows. */
    void
    assemble_stiffness_rows(const std::vector<SlaveNodeConditions> &nodes);
    /** The rows of one slave node: the conditions of its set. */
    void
    assemble_slave_node_rows(const SlaveNodeConditions &node);
    /** v . (D u^1 - M u^2)_j = value of @p node in @p row, scaled to the
     * size of K. */
    void
    add_jump_row(const SlaveNodeConditions    &node,
                 const types::global_dof_index row,
                 const Tensor<1, 2>           &v,
                 double                        value);
    /** w . lambda_j = 0 of @p node in @p row. */
    void
    add_traction_row(const SlaveNodeConditions    &node,
                     const types::global_dof_index row,
                     const Tensor<1, 2>           &w);
    void
    add_row(const types::global_dof_index row, const double right_hand_side);

    const ElasticBody       *slave        = nullptr;
    const ElasticBody       *master       = nullptr;
    const SlaveCondensation *condensation = nullptr;
    const MortarInterface   *mortar       = nullptr;
    /** The gap rows are scaled like the rows of K^1 they replace: by
     * body 1's Young's modulus. */
    double                         row_scale = 1;
    TrilinosWrappers::SparseMatrix matrix;
    TrilinosWrappers::MPI::Vector  rhs;
    /** The row being built (add_row). */
    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
  };
} // namespace coulomb_adapt

#endif
