#include <deal.II/base/mpi.h>

#include <coulomb_adapt/contact/condensed_newton_system.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace coulomb_adapt
{
  // The combined index space, the K^1 rows of the slave DoFs (gathered on
  // all ranks) and the master-to-slave coupling.
  void
  SlaveCondensation::reinit(const MortarInterface &mortar,
                            const ElasticBody     &slave,
                            const ElasticBody     &master)
  {
    const auto        &nodes   = mortar.slave_nodes();
    const auto        &M       = mortar.master_coupling();
    const unsigned int n_slave = nodes.size();
    communicator               = slave.triangulation().get_communicator();
    weights                    = mortar.slave_weights();

    const IndexSet &owned_1 = slave.locally_owned_dof_set();
    const IndexSet &owned_2 = master.locally_owned_dof_set();
    offset                  = slave.dof_handler().n_dofs();
    owned.clear();
    owned.set_size(offset + master.dof_handler().n_dofs());
    owned.add_indices(owned_1);
    owned.add_indices(owned_2, offset);
    owned.compress();

    // Rows of K^1 and f^1 at the slave DoFs, packed as
    // [node, component, rhs, n, col_0, value_0, ...].
    std::vector<double> packed;
    owned_slave_nodes.clear();
    const auto &K1 = slave.system_matrix();
    const auto &f1 = slave.system_rhs();
    for (unsigned int j = 0; j < n_slave; ++j)
      if (owned_1.is_element(nodes[j].dofs[0]))
        {
          owned_slave_nodes.push_back(j);
          for (unsigned int c = 0; c < 2; ++c)
            {
              const auto row = nodes[j].dofs[c];
              // (Nodes beyond the master's edge never touch: they may be
              // supported, their rows stay those of K^1.)
              AssertThrow(!mortar.is_covered(j) ||
                            !slave.constraints().is_constrained(row),
                          ExcMessage("A contact node of body 1 at (" +
                                     std::to_string(nodes[j].position[0]) +
                                     ", " +
                                     std::to_string(nodes[j].position[1]) +
                                     ") has a Dirichlet condition; contact "
                                     "nodes must be free."));
              packed.push_back(j);
              packed.push_back(c);
              packed.push_back(f1(row));
              packed.push_back(K1.row_length(row));
              for_each_entry(K1,
                             row,
                             [&](const auto column, const double value) {
                               packed.push_back(column);
                               packed.push_back(value);
                             });
            }
        }
    slave_rows.assign(n_slave, {});
    for (const auto &values : Utilities::MPI::all_gather(communicator, packed))
      for (std::size_t i = 0; i < values.size();)
        {
          SlaveRow &row = slave_rows[static_cast<unsigned int>(values[i])]
                                    [static_cast<unsigned int>(values[i + 1])];
          row.rhs              = values[i + 2];
          const auto n_entries = static_cast<std::size_t>(values[i + 3]);
          i += 4;
          for (std::size_t e = 0; e < n_entries; ++e, i += 2)
            {
              row.columns.push_back(
                static_cast<types::global_dof_index>(values[i]));
              row.values.push_back(values[i + 1]);
            }
        }

    master_dof_node.clear();
    const auto &master_nodes = mortar.master_nodes();
    for (unsigned int l = 0; l < master_nodes.size(); ++l)
      for (unsigned int c = 0; c < 2; ++c)
        master_dof_node[master_nodes[l].dofs[c]] = {l, c};
    master_to_slave.assign(master_nodes.size(), {});
    for (unsigned int j = 0; j < n_slave; ++j)
      for (const auto &[l, m] : M[j])
        master_to_slave[l].emplace_back(j, m);
  }



  // lambda_j = (f^1 - K^1 u^1)_j / D_jj at the owned slave nodes, gathered
  // on every rank. The multipliers are differences of large nodal forces:
  // their round-off bounds what the complementarity residual can reach.
  SlaveCondensation::Multipliers
  SlaveCondensation::multipliers(const MortarInterface               &mortar,
                                 const TrilinosWrappers::MPI::Vector &u1) const
  {
    // [j, lambda_x, lambda_y] of the slave nodes whose rows this rank owns.
    std::vector<double> packed;
    double              round_off = 0;
    for (const unsigned int j : owned_slave_nodes)
      {
        Tensor<1, 2> lambda;
        for (unsigned int c = 0; c < 2; ++c)
          {
            const SlaveRow &k  = slave_rows[j][c];
            double          Ku = 0, magnitude = std::abs(k.rhs);
            for (unsigned int e = 0; e < k.columns.size(); ++e)
              {
                Ku += k.values[e] * u1(k.columns[e]);
                magnitude += std::abs(k.values[e] * u1(k.columns[e]));
              }
            lambda[c] = mortar.is_covered(j) ? (k.rhs - Ku) / weights[j] : 0.;
            // Round-off of this difference of nodal forces, and of a
            // backward-stable solve's residual in the same row.
            if (mortar.is_covered(j))
              round_off = std::max(round_off,
                                   (k.columns.size() + 1) *
                                     std::numeric_limits<double>::epsilon() *
                                     magnitude / weights[j]);
          }
        packed.insert(packed.end(), {double(j), lambda[0], lambda[1]});
      }
    Multipliers result;
    result.round_off = Utilities::MPI::max(round_off, communicator);
    result.lambda.resize(slave_rows.size());
    for (const auto &v : Utilities::MPI::all_gather(communicator, packed))
      for (std::size_t i = 0; i < v.size(); i += 3)
        result.lambda[static_cast<unsigned int>(v[i])] =
          Tensor<1, 2>({v[i + 1], v[i + 2]});
    return result;
  }



  std::vector<SlaveNodeConditions>
  slave_node_conditions(const SlaveCondensation             &condensation,
                        const MortarInterface               &mortar,
                        const ElasticBody                   &master,
                        const std::vector<ContactNodeState> &states,
                        const std::vector<double> &previous_weighted_slip,
                        const double               friction_coefficient)
  {
    const auto &nodes        = mortar.slave_nodes();
    const auto &master_nodes = mortar.master_nodes();
    const auto &D            = mortar.slave_weights();
    const auto &M            = mortar.master_coupling();
    const auto &gaps         = mortar.weighted_initial_gaps();
    const auto &constraints  = master.constraints();

    std::vector<SlaveNodeConditions> result;
    for (const unsigned int j : condensation.owned_slave_nodes)
      {
        SlaveNodeConditions node;
        node.index   = j;
        node.dofs    = nodes[j].dofs;
        node.normal  = nodes[j].normal;
        node.tangent = nodes[j].tangent;
        node.weight  = D[j];
        node.active =
          mortar.is_covered(j) && states[j].status != ContactStatus::open;
        node.stick                = states[j].status == ContactStatus::stick;
        node.weighted_gap         = gaps[j];
        node.weighted_slip        = previous_weighted_slip[j];
        node.slip_sign            = states[j].slip_sign;
        node.friction_coefficient = friction_coefficient;
        for (const auto &[l, m] : M[j])
          {
            SlaveNodeConditions::Coupling coupling;
            for (unsigned int d = 0; d < 2; ++d)
              {
                coupling.dofs[d] =
                  condensation.offset + master_nodes[l].dofs[d];
                coupling.constrained[d] =
                  constraints.is_constrained(master_nodes[l].dofs[d]);
              }
            coupling.value = m;
            node.couplings.push_back(coupling);
          }
        result.push_back(node);
      }
    return result;
  }
} // namespace coulomb_adapt
