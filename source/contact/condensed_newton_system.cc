#include <deal.II/base/mpi.h>

#include <coulomb_adapt/contact/condensed_newton_system.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace coulomb_adapt
{
  namespace
  {
    std::string
    node_name(const MortarInterface::Node &node)
    {
      return "A contact node of body 1 at (" +
             std::to_string(node.position[0]) + ", " +
             std::to_string(node.position[1]) + ")";
    }



    // The Dirichlet data a covered slave node may carry: a fixed Cartesian
    // component along the contact surface, which takes the place of the
    // tangential contact condition. A fixed normal displacement would
    // contradict the normal condition (or, with the gap closed, make the
    // pressure the support's reaction), and a node fixed in both
    // components cannot take part in the contact at all. An empty string
    // if the node is acceptable, the reason otherwise.
    std::string
    refused_dirichlet_data(const MortarInterface::Node     &node,
                           const AffineConstraints<double> &constraints)
    {
      const std::array<bool, 2> fixed = {
        {constraints.is_constrained(node.dofs[0]),
         constraints.is_constrained(node.dofs[1])}};
      for (unsigned int c = 0; c < 2; ++c)
        if (fixed[c] &&
            !constraints.get_constraint_entries(node.dofs[c])->empty())
          return node_name(node) +
                 " is constrained to other nodes (a hanging node): contact "
                 "nodes must be nodes of both neighbouring faces.";
      if (fixed[0] && fixed[1])
        return node_name(node) +
               " has a Dirichlet condition on both components (a clamped "
               "curve or a point support): a node that faces body 2 must be "
               "free to move along its contact normal. Fix at most the "
               "component along the contact surface there (a roller on a "
               "symmetry line), or end the support before the contact "
               "surface.";
      for (unsigned int c = 0; c < 2; ++c)
        if (fixed[c] &&
            std::abs(node.normal[c]) >= std::abs(node.normal[1 - c]))
          return node_name(node) + " has its " + (c == 0 ? "x" : "y") +
                 " component fixed by a Dirichlet condition, along its "
                 "contact normal n = (" +
                 std::to_string(node.normal[0]) + ", " +
                 std::to_string(node.normal[1]) +
                 ") rather than along the contact surface: the support "
                 "would fix the gap that the contact condition decides. "
                 "Only the component along the contact surface may be "
                 "fixed on a contact node (a roller on a symmetry line "
                 "that meets the surface at a right angle).";
      return "";
    }



    // Whether a Dirichlet condition fixes @p row, and to which value (zero
    // if none), appended to @p packed.
    void
    pack_dirichlet_data(const AffineConstraints<double> &constraints,
                        const types::global_dof_index    row,
                        std::vector<double>             &packed)
    {
      const bool fixed = constraints.is_constrained(row);
      packed.push_back(fixed);
      packed.push_back(fixed ? constraints.get_inhomogeneity(row) : 0.);
    }



    // Rows of K^1 and f^1 at the slave DoFs this rank owns, packed as
    // [node, component, fixed, fixed value, rhs, n, col_0, value_0, ...],
    // and the owned slave nodes. @p refused receives the first reason a
    // covered node's Dirichlet data cannot be accepted.
    std::vector<double>
    pack_slave_rows(const MortarInterface     &mortar,
                    const ElasticBody         &slave,
                    std::vector<unsigned int> &owned_slave_nodes,
                    std::string               &refused)
    {
      const auto         &nodes   = mortar.slave_nodes();
      const IndexSet     &owned_1 = slave.locally_owned_dof_set();
      const auto         &K1      = slave.system_matrix();
      const auto         &f1      = slave.system_rhs();
      std::vector<double> packed;
      for (unsigned int j = 0; j < nodes.size(); ++j)
        if (owned_1.is_element(nodes[j].dofs[0]))
          {
            owned_slave_nodes.push_back(j);
            // (Nodes beyond the master's edge never touch: they may be
            // supported, their rows stay those of K^1.)
            if (mortar.is_covered(j) && refused.empty())
              refused = refused_dirichlet_data(nodes[j], slave.constraints());
            for (unsigned int c = 0; c < 2; ++c)
              {
                const auto row = nodes[j].dofs[c];
                packed.push_back(j);
                packed.push_back(c);
                pack_dirichlet_data(slave.constraints(), row, packed);
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
      return packed;
    }



    // The gathered rows of all ranks into the condensation's slave rows
    // and roller data.
    void
    unpack_slave_rows(const std::vector<std::vector<double>> &gathered,
                      const MortarInterface                  &mortar,
                      SlaveCondensation                      &condensation)
    {
      for (const auto &values : gathered)
        for (std::size_t i = 0; i < values.size();)
          {
            const auto j = static_cast<unsigned int>(values[i]);
            const auto c = static_cast<unsigned int>(values[i + 1]);
            if (values[i + 2] != 0 && mortar.is_covered(j))
              {
                condensation.fixed_component[j] = c;
                condensation.fixed_value[j]     = values[i + 3];
              }
            SlaveCondensation::SlaveRow &row = condensation.slave_rows[j][c];
            row.rhs                          = values[i + 4];
            const auto n_entries = static_cast<std::size_t>(values[i + 5]);
            i += 6;
            for (std::size_t e = 0; e < n_entries; ++e, i += 2)
              {
                row.columns.push_back(
                  static_cast<types::global_dof_index>(values[i]));
                row.values.push_back(values[i + 1]);
              }
          }
    }



    // The Dirichlet data of the master nodes this rank owns, packed as
    // [node, fixed_x, value_x, fixed_y, value_y].
    std::vector<double>
    pack_master_dirichlet_data(const MortarInterface &mortar,
                               const ElasticBody     &master)
    {
      const auto         &master_nodes = mortar.master_nodes();
      const IndexSet     &owned_2      = master.locally_owned_dof_set();
      std::vector<double> master_packed;
      for (unsigned int l = 0; l < master_nodes.size(); ++l)
        if (owned_2.is_element(master_nodes[l].dofs[0]))
          {
            master_packed.push_back(l);
            for (unsigned int c = 0; c < 2; ++c)
              pack_dirichlet_data(master.constraints(),
                                  master_nodes[l].dofs[c],
                                  master_packed);
          }
      return master_packed;
    }



    void
    unpack_master_dirichlet_data(
      const std::vector<std::vector<double>> &gathered,
      SlaveCondensation                      &condensation)
    {
      for (const auto &values : gathered)
        for (std::size_t i = 0; i < values.size(); i += 5)
          {
            const auto l = static_cast<unsigned int>(values[i]);
            for (unsigned int c = 0; c < 2; ++c)
              {
                condensation.master_fixed[l][c] = values[i + 1 + 2 * c] != 0;
                condensation.master_fixed_value[l][c] = values[i + 2 + 2 * c];
              }
          }
    }
  } // namespace



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

    offset = slave.dof_handler().n_dofs();
    owned.clear();
    owned.set_size(offset + master.dof_handler().n_dofs());
    owned.add_indices(slave.locally_owned_dof_set());
    owned.add_indices(master.locally_owned_dof_set(), offset);
    owned.compress();

    std::string refused;
    owned_slave_nodes.clear();
    const std::vector<double> packed =
      pack_slave_rows(mortar, slave, owned_slave_nodes, refused);
    // Every rank stops, with the first rank's message.
    for (const auto &message :
         Utilities::MPI::all_gather(communicator, refused))
      AssertThrow(message.empty(), ExcMessage(message));

    slave_rows.assign(n_slave, {});
    fixed_component.assign(n_slave, -1);
    fixed_value.assign(n_slave, 0.);
    unpack_slave_rows(Utilities::MPI::all_gather(communicator, packed),
                      mortar,
                      *this);

    // The master nodes' Dirichlet data, gathered: a slave node's rows
    // couple to master DoFs that its rank need not see. A constrained
    // DoF is zero in the Newton solve (its row's right hand side is zero:
    // deal.II fills in the value when the solution is distributed), so
    // the conditions that couple to it take its value instead.
    const auto &master_nodes = mortar.master_nodes();
    master_fixed.assign(master_nodes.size(), {{false, false}});
    master_fixed_value.assign(master_nodes.size(), {{0., 0.}});
    unpack_master_dirichlet_data(
      Utilities::MPI::all_gather(communicator,
                                 pack_master_dirichlet_data(mortar, master)),
      *this);

    master_dof_node.clear();
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
            // (A fixed component's row is its Dirichlet condition, not an
            // equation of the body: no round-off of a nodal force.)
            if (static_cast<int>(c) == fixed_component[j])
              continue;
            // Round-off of this difference of nodal forces, and of a
            // backward-stable solve's residual in the same row.
            if (mortar.is_covered(j))
              round_off = std::max(round_off,
                                   (k.columns.size() + 1) *
                                     std::numeric_limits<double>::epsilon() *
                                     magnitude / weights[j]);
          }
        // A roller: lambda = lambda_n n, from the free component's row.
        if (fixed_component[j] >= 0)
          {
            const unsigned int free   = 1 - fixed_component[j];
            const Tensor<1, 2> normal = mortar.slave_nodes()[j].normal;
            lambda                    = lambda[free] / normal[free] * normal;
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
                        const std::vector<ContactNodeState> &states,
                        const std::vector<double> &previous_weighted_slip,
                        const double               friction_coefficient)
  {
    const auto &nodes        = mortar.slave_nodes();
    const auto &master_nodes = mortar.master_nodes();
    const auto &D            = mortar.slave_weights();
    const auto &M            = mortar.master_coupling();
    const auto &gaps         = mortar.weighted_initial_gaps();

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
        node.fixed_component      = condensation.fixed_component[j];
        node.fixed_value          = condensation.fixed_value[j];
        for (const auto &[l, m] : M[j])
          {
            SlaveNodeConditions::Coupling coupling;
            for (unsigned int d = 0; d < 2; ++d)
              {
                coupling.dofs[d] =
                  condensation.offset + master_nodes[l].dofs[d];
                coupling.constrained[d] = condensation.master_fixed[l][d];
                coupling.fixed_value[d] = condensation.master_fixed_value[l][d];
              }
            coupling.value = m;
            node.couplings.push_back(coupling);
          }
        result.push_back(node);
      }
    return result;
  }
} // namespace coulomb_adapt
