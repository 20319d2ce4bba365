#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <coulomb_adapt/contact/row_replacing_contact_system.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <cmath>
#include <set>

namespace coulomb_adapt
{
  // K^1 and K^2 (shifted), the slave rows (both K^1 rows of the node, the
  // node's own DoFs and the coupled master DoFs), and in the master rows
  // the K^1 rows of the coupled slave nodes.
  void
  RowReplacingContactSystem::reinit(const MortarInterface   &mortar,
                                    const ElasticBody       &slave,
                                    const ElasticBody       &master,
                                    const SlaveCondensation &condensation)
  {
    this->slave        = &slave;
    this->master       = &master;
    this->condensation = &condensation;
    this->mortar       = &mortar;
    row_scale          = slave.description().material.youngs_modulus;

    const auto            &nodes        = mortar.slave_nodes();
    const auto            &master_nodes = mortar.master_nodes();
    const auto            &M            = mortar.master_coupling();
    const auto            &rows         = condensation.slave_rows;
    const auto             offset       = condensation.offset;
    const auto            &owned        = condensation.owned;
    DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
    for (const auto row : slave.locally_owned_dof_set())
      for_each_entry(slave.system_matrix(),
                     row,
                     [&](const auto column, const double) {
                       dsp.add(row, column);
                     });
    for (const unsigned int j : condensation.owned_slave_nodes)
      for (unsigned int c = 0; c < 2; ++c)
        {
          const auto row = nodes[j].dofs[c];
          for (unsigned int d = 0; d < 2; ++d)
            {
              dsp.add_entries(row,
                              rows[j][d].columns.begin(),
                              rows[j][d].columns.end());
              dsp.add(row, nodes[j].dofs[d]);
              for (const auto &[l, m] : M[j])
                dsp.add(row, offset + master_nodes[l].dofs[d]);
            }
        }
    for (const auto row : master.locally_owned_dof_set())
      {
        for_each_entry(master.system_matrix(),
                       row,
                       [&](const auto column, const double) {
                         dsp.add(offset + row, offset + column);
                       });
        const auto node = condensation.master_dof_node.find(row);
        if (node != condensation.master_dof_node.end() &&
            !master.constraints().is_constrained(row))
          for (const auto &[j, m] :
               condensation.master_to_slave[node->second.first])
            {
              // A roller's force is lambda_n n, from its free row.
              const int  fixed = condensation.fixed_component[j];
              const auto c     = fixed >= 0 ? 1 - fixed : node->second.second;
              dsp.add_entries(offset + row,
                              rows[j][c].columns.begin(),
                              rows[j][c].columns.end());
            }
      }
    matrix.reinit(owned, owned, dsp, condensation.communicator);
    rhs.reinit(owned, condensation.communicator);
  }



  void
  RowReplacingContactSystem::add_row(const types::global_dof_index row,
                                     const double right_hand_side)
  {
    matrix.add(row, columns.size(), columns.data(), values.data());
    rhs(row) += right_hand_side;
    columns.clear();
    values.clear();
  }



  void
  RowReplacingContactSystem::assemble(
    const std::vector<SlaveNodeConditions> &nodes)
  {
    matrix = 0;
    rhs    = 0;
    assemble_stiffness_rows(nodes);
    for (const auto &node : nodes)
      assemble_slave_node_rows(node);
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  void
  RowReplacingContactSystem::assemble_stiffness_rows(
    const std::vector<SlaveNodeConditions> &nodes)
  {
    const auto &K1           = slave->system_matrix();
    const auto &K2           = master->system_matrix();
    const auto &f1           = slave->system_rhs();
    const auto &f2           = master->system_rhs();
    const auto &D            = condensation->weights;
    const auto  offset       = condensation->offset;
    const auto &mortar_nodes = mortar->slave_nodes();

    std::set<types::global_dof_index> slave_dofs;
    for (const auto &node : nodes)
      for (unsigned int c = 0; c < 2; ++c)
        slave_dofs.insert(node.dofs[c]);

    for (const auto row : slave->locally_owned_dof_set())
      if (slave_dofs.count(row) == 0)
        {
          for_each_entry(K1, row, [&](const auto column, const double value) {
            columns.push_back(column);
            values.push_back(value);
          });
          add_row(row, f1(row));
        }
    for (const auto row : master->locally_owned_dof_set())
      {
        for_each_entry(K2, row, [&](const auto column, const double value) {
          columns.push_back(offset + column);
          values.push_back(value);
        });
        double     right_hand_side = f2(row);
        const auto node            = condensation->master_dof_node.find(row);
        if (node != condensation->master_dof_node.end() &&
            !master->constraints().is_constrained(row))
          for (const auto &[j, m] :
               condensation->master_to_slave[node->second.first])
            {
              // M_jl lambda_j: lambda_j = (f^1 - K^1 u^1)_j / D_jj, or at
              // a roller lambda_n n with lambda_n from the free row.
              const int    fixed  = condensation->fixed_component[j];
              double       factor = m / D[j];
              unsigned int c      = node->second.second;
              if (fixed >= 0)
                {
                  const auto &n = mortar_nodes[j].normal;
                  factor *= n[c] / n[1 - fixed];
                  c = 1 - fixed;
                }
              const auto &k = condensation->slave_rows[j][c];
              for (unsigned int e = 0; e < k.columns.size(); ++e)
                {
                  columns.push_back(k.columns[e]);
                  values.push_back(factor * k.values[e]);
                }
              right_hand_side += factor * k.rhs;
            }
        add_row(offset + row, right_hand_side);
      }
  }



  // v . (D u^1 - M u^2)_j = value, scaled to the size of K. A component
  // a roller fixes is known: its term goes to the right hand side.
  void
  RowReplacingContactSystem::add_jump_row(const SlaveNodeConditions    &node,
                                          const types::global_dof_index row,
                                          const Tensor<1, 2>           &v,
                                          double                        value)
  {
    const double D     = node.weight;
    const double scale = row_scale / D;
    for (unsigned int d = 0; d < 2; ++d)
      {
        if (static_cast<int>(d) == node.fixed_component)
          value -= D * v[d] * node.fixed_value;
        else
          {
            columns.push_back(node.dofs[d]);
            values.push_back(scale * D * v[d]);
          }
        for (const auto &coupling : node.couplings)
          {
            columns.push_back(coupling.dofs[d]);
            values.push_back(-scale * coupling.value * v[d]);
            if (coupling.constrained[d])
              value += coupling.value * v[d] * coupling.fixed_value[d];
          }
      }
    add_row(row, scale * value);
  }



  // w . (K^1 u^1)_j = w . f^1_j, i.e. w . lambda_j = 0.
  void
  RowReplacingContactSystem::add_traction_row(const SlaveNodeConditions &node,
                                              const types::global_dof_index row,
                                              const Tensor<1, 2>           &w)
  {
    double right_hand_side = 0;
    for (unsigned int d = 0; d < 2; ++d)
      {
        const auto &k = condensation->slave_rows[node.index][d];
        for (unsigned int e = 0; e < k.columns.size(); ++e)
          {
            columns.push_back(k.columns[e]);
            values.push_back(w[d] * k.values[e]);
          }
        right_hand_side += w[d] * k.rhs;
      }
    add_row(row, right_hand_side);
  }



  void
  RowReplacingContactSystem::assemble_slave_node_rows(
    const SlaveNodeConditions &node)
  {
    const Tensor<1, 2> &n = node.normal;
    const Tensor<1, 2> &t = node.tangent;

    // A roller: its fixed component's row stays K^1's, its Dirichlet
    // condition; the free row is lambda_n = 0 or the normal condition.
    if (node.fixed_component >= 0)
      {
        const unsigned int fixed = node.fixed_component;
        Tensor<1, 2>       e_fixed, e_free;
        e_fixed[fixed]    = 1;
        e_free[1 - fixed] = 1;
        add_traction_row(node, node.dofs[fixed], e_fixed);
        if (node.active)
          add_jump_row(node, node.dofs[1 - fixed], n, node.weighted_gap);
        else
          add_traction_row(node, node.dofs[1 - fixed], e_free);
        return;
      }

    const unsigned int normal_component =
      std::abs(n[1]) >= std::abs(n[0]) ? 1 : 0;
    const auto row_n = node.dofs[normal_component];
    const auto row_t = node.dofs[1 - normal_component];
    if (!node.active)
      {
        add_traction_row(node, node.dofs[0], Tensor<1, 2>({1., 0.}));
        add_traction_row(node, node.dofs[1], Tensor<1, 2>({0., 1.}));
      }
    else
      {
        add_jump_row(node, row_n, n, node.weighted_gap);
        if (node.stick)
          add_jump_row(node, row_t, t, node.weighted_slip);
        else
          add_traction_row(node,
                           row_t,
                           t - node.friction_coefficient * node.slip_sign * n);
      }
  }



  LinearSolverReport
  RowReplacingContactSystem::solve(
    const std::vector<std::vector<double>> &near_null_space,
    const parameters::LinearSolver         &settings,
    TrilinosWrappers::MPI::Vector          &solution)
  {
    return solve_linear_system(matrix,
                               solution,
                               rhs,
                               near_null_space,
                               settings,
                               /*symmetric=*/false);
  }
} // namespace coulomb_adapt
