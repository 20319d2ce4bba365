#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/bodies/rigid_motion_gram.h>
#include <coulomb_adapt/contact/contact_diagnosis.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/solvers/linear_solver.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

namespace coulomb_adapt
{
  std::string
  to_string(const ContactStatus status)
  {
    switch (status)
      {
        case ContactStatus::open:
          return "open";
        case ContactStatus::stick:
          return "stick";
        default:
          return "slip";
      }
  }






  ContactSolver::ContactSolver(
    ElasticBody &                   slave,
    ElasticBody &                   master,
    const parameters::Contact &     contact_parameters,
    const parameters::LinearSolver &solver_parameters,
    const ConditionalOStream &      pcout)
    : slave(slave)
    , master(master)
    , contact_parameters(contact_parameters)
    , solver_parameters(solver_parameters)
    , pcout(pcout)
    , mpi_communicator(slave.triangulation().get_communicator())
    , mu(contact_parameters.friction_coefficient)
  {}



  // The mortar integrals, the K^1 rows of the slave DoFs (gathered on all
  // ranks: the master rows need them) and the sparsity of the condensed
  // system, which does not depend on the sets.
  void
  ContactSolver::setup()
  {
    mortar.reinit(slave, master);
    const auto &nodes = mortar.slave_nodes();
    const auto &D     = mortar.slave_weights();
    const auto &M     = mortar.master_coupling();
    const unsigned int n_slave = nodes.size();
    AssertThrow(n_slave > 0,
                ExcMessage("The contact boundary of body 1 is empty."));

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
              for_each_entry(K1, row, [&](const auto column, const double value) {
                packed.push_back(column);
                packed.push_back(value);
              });
            }
        }
    slave_rows.assign(n_slave, {});
    for (const auto &values :
         Utilities::MPI::all_gather(mpi_communicator, packed))
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

    // c = scale E_c / D_jj with the combined modulus E_c = E1 E2 / (E1 +
    // E2), which follows the softer body: with the stiffer one's modulus a
    // soft partner makes c and the residual scale meaningless.
    const double E = combined_modulus();
    complementarity_constant.resize(n_slave);
    for (unsigned int j = 0; j < n_slave; ++j)
      complementarity_constant[j] =
        contact_parameters.complementarity_scale * E / D[j];
    // The gap rows are scaled like the rows of K^1 they replace.
    row_scale = slave.description().material.youngs_modulus;

    iterative = solver_parameters.type == "amg" ||
                (solver_parameters.type == "auto" &&
                 owned.size() > solver_parameters.max_dofs_for_direct_contact);
    if (iterative)
      eliminated_system.reinit(K1,
                               master.system_matrix(),
                               f1,
                               master.system_rhs(),
                               owned,
                               offset,
                               mpi_communicator);
    else
      build_row_replacing_pattern();

    // The states (sets and slip history) persist from one load step to the
    // next on the same mesh.
    const bool first_step = states.size() != n_slave;
    if (first_step)
      {
        states.assign(n_slave, {});
        previous_weighted_slip.assign(n_slave, 0.);
      }
    for (unsigned int j = 0; j < n_slave; ++j)
      {
        states[j].position = nodes[j].position;
        states[j].normal   = nodes[j].normal;
        states[j].tangent  = nodes[j].tangent;
        states[j].weight   = D[j];
      }
    // Which rigid motions of body 1 its Dirichlet data hold: once per
    // load step (a pass over its cells), for every support test of the
    // Newton steps.
    support_centre = Point<2>();
    for (const auto &s : states)
      support_centre += s.position / static_cast<double>(states.size());
    slave_support_gram = slave.support_gram(support_centre);
    if (first_step)
      {
        initialize_sets();
        if (!warm_start_states.empty())
          transfer_warm_start_sets();
      }
  }



  // Sparsity of the row-replacing system, which does not depend on the
  // sets: K^1 and K^2 (shifted), the slave rows (both K^1 rows of the
  // node, the node's own DoFs and the coupled master DoFs), and in the
  // master rows the K^1 rows of the coupled slave nodes.
  void
  ContactSolver::build_row_replacing_pattern()
  {
    const auto &nodes        = mortar.slave_nodes();
    const auto &master_nodes = mortar.master_nodes();
    const auto &M            = mortar.master_coupling();
    const auto &K1           = slave.system_matrix();
    const IndexSet &owned_1  = slave.locally_owned_dof_set();
    const IndexSet &owned_2  = master.locally_owned_dof_set();
    DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
    const auto &K2 = master.system_matrix();
    for (const auto row : owned_1)
      for_each_entry(K1, row, [&](const auto column, const double) {
        dsp.add(row, column);
      });
    for (const unsigned int j : owned_slave_nodes)
      for (unsigned int c = 0; c < 2; ++c)
        {
          const auto row = nodes[j].dofs[c];
          for (unsigned int d = 0; d < 2; ++d)
            {
              dsp.add_entries(row,
                              slave_rows[j][d].columns.begin(),
                              slave_rows[j][d].columns.end());
              dsp.add(row, nodes[j].dofs[d]);
              for (const auto &[l, m] : M[j])
                dsp.add(row, offset + master_nodes[l].dofs[d]);
            }
        }
    for (const auto row : owned_2)
      {
        for_each_entry(K2, row, [&](const auto column, const double) {
          dsp.add(offset + row, offset + column);
        });
        const auto node = master_dof_node.find(row);
        if (node != master_dof_node.end() &&
            !master.constraints().is_constrained(row))
          for (const auto &[j, m] : master_to_slave[node->second.first])
            dsp.add_entries(offset + row,
                            slave_rows[j][node->second.second].columns.begin(),
                            slave_rows[j][node->second.second].columns.end());
      }
    matrix.reinit(owned, owned, dsp, mpi_communicator);
    rhs.reinit(owned, mpi_communicator);
  }



  // Nearest previous node by position: the interface is a curve, and the
  // meshes of two cycles resolve it differently.
  void
  ContactSolver::transfer_warm_start_sets()
  {
    std::vector<ContactNodeState> transferred = states;
    unsigned int                  n_active    = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        if (!mortar.is_covered(j))
          continue;
        const ContactNodeState *nearest = nullptr;
        double                  best    = std::numeric_limits<double>::max();
        for (const auto &p : warm_start_states)
          {
            const double d = p.position.distance_square(states[j].position);
            if (d < best)
              best = d, nearest = &p;
          }
        transferred[j].status    = nearest->status;
        transferred[j].slip_sign = nearest->slip_sign;
        if (mu == 0 && transferred[j].status == ContactStatus::stick)
          transferred[j].status = ContactStatus::slip;
        n_active += (transferred[j].status != ContactStatus::open);
      }
    if (n_active > 0 || holds_all_rigid_motions(slave_support_gram))
      states = transferred;
    warm_start_states.clear();
  }



  void
  ContactSolver::warm_start_from(const std::vector<ContactNodeState> &previous)
  {
    warm_start_states = previous;
  }



  // Nodes that touch in the initial configuration start active: stuck if
  // there is friction, which holds a floating body 1 in the first step.
  void
  ContactSolver::initialize_sets()
  {
    const auto &gaps = mortar.weighted_initial_gaps();
    const auto &D    = mortar.slave_weights();
    // The interface's extent: the same on every rank.
    double size = 0;
    for (const auto &s : states)
      size = std::max(size, s.position.distance(states.front().position));
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        const bool touching =
          mortar.is_covered(j) && gaps[j] / D[j] <= 1e-10 * size;
        states[j].status    = !touching ? ContactStatus::open :
                              mu > 0    ? ContactStatus::stick :
                                          ContactStatus::slip;
        states[j].slip_sign = 1;
      }
  }



  // With the current sets, is body 1 held? Without stick nodes nothing
  // resists a rigid slide along the interface, and without active nodes
  // nothing holds it at all, unless its own Dirichlet data do: the system
  // would be singular, and the static problem has no solution.
  void
  ContactSolver::check_support(const unsigned int step) const
  {
    unsigned int n_active = 0, n_stick = 0;
    for (const auto &s : states)
      if (s.status != ContactStatus::open)
        {
          ++n_active;
          n_stick += (s.status == ContactStatus::stick);
        }
    const std::string where =
      "Newton step " + std::to_string(step) + ": body 1 (" + slave.name() +
      ") ";
    if (n_active == 0 && !holds_all_rigid_motions(slave_support_gram))
      throw ContactDiagnosis(where + "has no active contact node and no "
                                     "Dirichlet support: nothing holds it "
                                     "(is it loaded towards body 2?).",
                             step - 1);
    if (n_stick == 0 && n_active > 0)
      {
        Tensor<1, 2> tangent;
        for (const auto &s : states)
          if (s.status != ContactStatus::open)
            tangent += s.tangent;
        tangent /= tangent.norm();
        if (!holds_translation_along(slave_support_gram, tangent))
          throw ContactDiagnosis(
            where +
            (mu == 0 ?
               "can slide freely along the frictionless interface: nothing "
               "holds it tangentially. Hold it with the scene's hold option "
               "(blocks, punch: 'Hold centre line'; hertz: 'Hold axis'; "
               "patch: 'Hold upper body') or use friction." :
               "would slide: in the contact sets of this step every active "
               "node slips and no Dirichlet data hold it tangentially, so "
               "the linear system is singular. " +
                 (step == 1 ?
                    std::string("") :
                    std::string("If the tangential load exceeds mu times "
                                "the normal load the static problem has no "
                                "equilibrium; otherwise the active set "
                                "iteration went astray (try another "
                                "'Contact/Complementarity scale').")) +
                 (step == 1 ? std::string("The tangential load exceeds mu "
                                          "times the normal load?") :
                              std::string())),
            step - 1);
      }
  }



  // Translations held, but perhaps not the rotation: a body resting on one
  // active node (a disc on a mesh coarser than its contact zone, or the
  // first step from the initial gap) or on nodes whose normals meet in one
  // point can turn about it. Each active node fixes n . u at its position,
  // a stick node t . u too: rows added to the Gram matrix of body 1's
  // supported rigid motions.
  bool
  ContactSolver::slave_rotation_free() const
  {
    // About the centroid of the active nodes: the rows of a small contact
    // zone far from the centre would otherwise look like a single point
    // (hertz at a load of 1e-7 with 23 stick nodes was reported free).
    Point<2>     centre;
    unsigned int n_active = 0;
    for (const auto &s : states)
      if (s.status != ContactStatus::open)
        {
          centre += s.position;
          ++n_active;
        }
    centre = (n_active > 0) ? centre / static_cast<double>(n_active) :
                              support_centre;
    FullMatrix<double> gram =
      move_rotation_centre(slave_support_gram, centre - support_centre);
    for (const auto &s : states)
      if (s.status != ContactStatus::open)
        {
          add_rigid_motion_constraint(gram, s.normal, s.position, centre);
          if (s.status == ContactStatus::stick)
            add_rigid_motion_constraint(gram, s.tangent, s.position, centre);
        }
    return !holds_all_rigid_motions(gram);
  }



  void
  ContactSolver::assemble_newton_system()
  {
    if (iterative)
      {
        eliminated_system.assemble(eliminated_slave_nodes());
        return;
      }
    matrix = 0;
    rhs    = 0;
    const auto &nodes        = mortar.slave_nodes();
    const auto &master_nodes = mortar.master_nodes();
    const auto &D            = mortar.slave_weights();
    const auto &M            = mortar.master_coupling();
    const auto &gaps         = mortar.weighted_initial_gaps();
    const auto &K1           = slave.system_matrix();
    const auto &K2           = master.system_matrix();
    const auto &f1           = slave.system_rhs();
    const auto &f2           = master.system_rhs();

    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    const auto add_row = [&](const types::global_dof_index row,
                             const double                  right_hand_side) {
      matrix.add(row, columns.size(), columns.data(), values.data());
      rhs(row) += right_hand_side;
      columns.clear();
      values.clear();
    };

    std::set<types::global_dof_index> slave_dofs;
    for (const unsigned int j : owned_slave_nodes)
      for (unsigned int c = 0; c < 2; ++c)
        slave_dofs.insert(nodes[j].dofs[c]);

    // Body 1 away from the contact nodes, and body 2: the stiffness rows.
    for (const auto row : slave.locally_owned_dof_set())
      if (slave_dofs.count(row) == 0)
        {
          for_each_entry(K1, row, [&](const auto column, const double value) {
            columns.push_back(column);
            values.push_back(value);
          });
          add_row(row, f1(row));
        }
    for (const auto row : master.locally_owned_dof_set())
      {
        for_each_entry(K2, row, [&](const auto column, const double value) {
          columns.push_back(offset + column);
          values.push_back(value);
        });
        double     right_hand_side = f2(row);
        const auto node            = master_dof_node.find(row);
        // Master rows receive M^T lambda = M^T D^-1 (f^1 - K^1 u^1).
        if (node != master_dof_node.end() &&
            !master.constraints().is_constrained(row))
          for (const auto &[j, m] : master_to_slave[node->second.first])
            {
              const SlaveRow &k = slave_rows[j][node->second.second];
              for (unsigned int e = 0; e < k.columns.size(); ++e)
                {
                  columns.push_back(k.columns[e]);
                  values.push_back(m / D[j] * k.values[e]);
                }
              right_hand_side += m / D[j] * k.rhs;
            }
        add_row(offset + row, right_hand_side);
      }

    // Slave nodes: the conditions of their set.
    for (const unsigned int j : owned_slave_nodes)
      {
        const ContactStatus status = states[j].status;
        const Tensor<1, 2> &n      = nodes[j].normal;
        const Tensor<1, 2> &t      = nodes[j].tangent;

        // v . (D u^1 - M u^2)_j = value, scaled to the size of K.
        const auto add_jump_row = [&](const types::global_dof_index row,
                                      const Tensor<1, 2> &          v,
                                      const double                  value) {
          const double scale = row_scale / D[j];
          for (unsigned int d = 0; d < 2; ++d)
            {
              columns.push_back(nodes[j].dofs[d]);
              values.push_back(scale * D[j] * v[d]);
              for (const auto &[l, m] : M[j])
                {
                  columns.push_back(offset + master_nodes[l].dofs[d]);
                  values.push_back(-scale * m * v[d]);
                }
            }
          add_row(row, scale * value);
        };
        // w . (K^1 u^1)_j = w . f^1_j, i.e. w . lambda_j = 0.
        const auto add_traction_row = [&](const types::global_dof_index row,
                                          const Tensor<1, 2> &          w) {
          double right_hand_side = 0;
          for (unsigned int d = 0; d < 2; ++d)
            {
              const SlaveRow &k = slave_rows[j][d];
              for (unsigned int e = 0; e < k.columns.size(); ++e)
                {
                  columns.push_back(k.columns[e]);
                  values.push_back(w[d] * k.values[e]);
                }
              right_hand_side += w[d] * k.rhs;
            }
          add_row(row, right_hand_side);
        };

        // The normal condition goes into the row of the displacement
        // component most aligned with n, so that it has a large diagonal
        // entry (pivoting, iterative solvers).
        const unsigned int normal_component =
          std::abs(n[1]) >= std::abs(n[0]) ? 1 : 0;
        const auto row_n = nodes[j].dofs[normal_component];
        const auto row_t = nodes[j].dofs[1 - normal_component];
        if (status == ContactStatus::open)
          {
            add_traction_row(nodes[j].dofs[0], Tensor<1, 2>({1., 0.}));
            add_traction_row(nodes[j].dofs[1], Tensor<1, 2>({0., 1.}));
          }
        else
          {
            add_jump_row(row_n, n, gaps[j]);
            // Stick: no tangential slip in this load step.
            if (status == ContactStatus::stick)
              add_jump_row(row_t, t, previous_weighted_slip[j]);
            else
              add_traction_row(row_t, t - mu * states[j].slip_sign * n);
          }
      }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  void
  ContactSolver::solve_newton_system()
  {
    TrilinosWrappers::MPI::Vector solution(owned, mpi_communicator);
    parameters::LinearSolver settings = solver_parameters;
    settings.type = iterative ? "amg" : "direct";
    // The multipliers are differences of large nodal forces (f - K u at the
    // slave rows): an iterative solve to 1e-10 leaves the complementarity
    // residual near 1e-9 (hertz), above the default Contact/Tolerance.
    settings.relative_tolerance =
      std::min(settings.relative_tolerance, 1e-12) * linear_tolerance_factor;
    if (iterative)
      last_linear_solve =
        eliminated_system.solve(near_null_space, settings, solution);
    else
      last_linear_solve = solve_linear_system(matrix,
                                              solution,
                                              rhs,
                                              {},
                                              settings,
                                              /*symmetric=*/false);

    TrilinosWrappers::MPI::Vector u1(slave.locally_owned_dof_set(),
                                     mpi_communicator);
    TrilinosWrappers::MPI::Vector u2(master.locally_owned_dof_set(),
                                     mpi_communicator);
    for (const auto i : slave.locally_owned_dof_set())
      u1(i) = solution(i);
    for (const auto i : master.locally_owned_dof_set())
      u2(i) = solution(offset + i);
    u1.compress(VectorOperation::insert);
    u2.compress(VectorOperation::insert);
    slave.set_solution(u1);
    master.set_solution(u2);
  }



  std::vector<EliminatedContactSystem::SlaveNode>
  ContactSolver::eliminated_slave_nodes() const
  {
    const auto &nodes        = mortar.slave_nodes();
    const auto &master_nodes = mortar.master_nodes();
    const auto &D            = mortar.slave_weights();
    const auto &M            = mortar.master_coupling();
    const auto &gaps         = mortar.weighted_initial_gaps();
    const auto &constraints  = master.constraints();

    std::vector<EliminatedContactSystem::SlaveNode> result;
    for (const unsigned int j : owned_slave_nodes)
      {
        EliminatedContactSystem::SlaveNode node;
        node.dofs    = nodes[j].dofs;
        node.normal  = nodes[j].normal;
        node.tangent = nodes[j].tangent;
        node.weight  = D[j];
        node.active  = mortar.is_covered(j) &&
                      states[j].status != ContactStatus::open;
        node.stick   = states[j].status == ContactStatus::stick;
        node.weighted_gap         = gaps[j];
        node.weighted_slip        = previous_weighted_slip[j];
        node.slip_sign            = states[j].slip_sign;
        node.friction_coefficient = mu;
        for (const auto &[l, m] : M[j])
          {
            EliminatedContactSystem::SlaveNode::Coupling coupling;
            for (unsigned int d = 0; d < 2; ++d)
              {
                coupling.dofs[d] = offset + master_nodes[l].dofs[d];
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



  // lambda_j = (f^1 - K^1 u^1)_j / D_jj at the owned slave nodes, the nodal
  // displacements of the interface, gaps and slips; everything gathered.
  void
  ContactSolver::evaluate_contact_state()
  {
    const auto &nodes        = mortar.slave_nodes();
    const auto &D            = mortar.slave_weights();
    const auto &u1           = slave.solution();
    const auto &u2           = master.solution();

    // The multipliers [j, lambda_x, lambda_y] of the slave nodes whose
    // rows this rank owns, gathered on every rank.
    std::vector<double> packed;
    double              round_off = 0;
    for (const unsigned int j : owned_slave_nodes)
      {
        Tensor<1, 2> lambda;
        for (unsigned int c = 0; c < 2; ++c)
          {
            const SlaveRow &k = slave_rows[j][c];
            double          Ku = 0, magnitude = std::abs(k.rhs);
            for (unsigned int e = 0; e < k.columns.size(); ++e)
              {
                Ku += k.values[e] * u1(k.columns[e]);
                magnitude += std::abs(k.values[e] * u1(k.columns[e]));
              }
            lambda[c] = mortar.is_covered(j) ? (k.rhs - Ku) / D[j] : 0.;
            // Round-off of this difference of nodal forces, and of a
            // backward-stable solve's residual in the same row.
            if (mortar.is_covered(j))
              round_off = std::max(round_off,
                                   (k.columns.size() + 1) *
                                     std::numeric_limits<double>::epsilon() *
                                     magnitude / D[j]);
          }
        packed.insert(packed.end(), {double(j), lambda[0], lambda[1]});
      }
    multiplier_round_off = Utilities::MPI::max(round_off, mpi_communicator);
    std::vector<Tensor<1, 2>> lambda(nodes.size());
    for (const auto &v : Utilities::MPI::all_gather(mpi_communicator, packed))
      for (std::size_t i = 0; i < v.size(); i += 3)
        lambda[static_cast<unsigned int>(v[i])] =
          Tensor<1, 2>({v[i + 1], v[i + 2]});
    const auto gaps = mortar.nodal_gaps(u1, u2);
    for (unsigned int j = 0; j < nodes.size(); ++j)
      {
        states[j].pressure            = lambda[j] * nodes[j].normal;
        states[j].tangential_traction = lambda[j] * nodes[j].tangent;
        states[j].facing_master       = mortar.is_covered(j);
        states[j].gap                 = gaps[j].gap;
        states[j].slip                = gaps[j].slip;
      }
  }



  // The primal-dual active set rule: the sets the complementarity
  // functions C_n, C_t of theory.md section 2 select at the current iterate.
  unsigned int
  ContactSolver::update_sets()
  {
    unsigned int n_changed = 0;
    // Within the convergence tolerance of the cone's edge, stick and slip
    // describe the same state (no slip increment, traction on the edge):
    // a node there keeps its status. Otherwise round-off decides, and the
    // sets can flip back and forth for ever (every slip node of the
    // previous step sits there in a load step that adds no load).
    double p_max = 0;
    for (const auto &s : states)
      p_max = std::max(p_max, std::abs(s.pressure));
    const double tie = contact_parameters.tolerance * p_max;
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        ContactNodeState &s = states[j];
        const auto [normal, trial] =
          trial_tractions(j, complementarity_constant[j]);
        ContactStatus status;
        int           sign = s.slip_sign;
        if (normal <= 0 || !mortar.is_covered(j))
          status = ContactStatus::open;
        else if (mu == 0)
          status = ContactStatus::slip;
        else
          {
            // The tie is measured with the natural constant, as the
            // residual is: with a small scale (c x 1e-3, stability case
            // 261) a slip node sliding backwards by a non-negligible
            // amount passed as a tie and the sets settled at a residual
            // of 2.3e-6.
            const auto natural = trial_tractions(j, natural_constant(j));
            const bool at_edge =
              std::abs(std::abs(natural.tangential) - mu * natural.normal) <=
                tie &&
              s.status != ContactStatus::open;
            if (at_edge ? s.status == ContactStatus::stick :
                          std::abs(trial) < mu * normal)
              status = ContactStatus::stick;
            else
              {
                status = ContactStatus::slip;
                sign   = trial >= 0 ? 1 : -1;
              }
          }
        if (status != s.status ||
            (status == ContactStatus::slip && mu > 0 && sign != s.slip_sign))
          ++n_changed;
        s.status    = status;
        s.slip_sign = sign;
      }
    return n_changed;
  }



  // max_j |C_n,j| / p and max_j |C_t,j| / p^2, p the largest pressure: zero
  // exactly when the contact conditions hold. Evaluated with the natural
  // constants c = E / D_jj, whatever scale drives the set update, so that
  // the tolerance means the same for every scale.
  double
  ContactSolver::complementarity_residual() const
  {
    const double p = largest_pressure();
    double residual = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      residual = std::max(residual, node_residual(j, p));
    return residual;
  }



  double
  ContactSolver::largest_pressure() const
  {
    double p = 0;
    for (const auto &s : states)
      p = std::max(p, std::abs(s.pressure));
    return p == 0 ? 1. : p;
  }



  // Node j's share of complementarity_residual(): how far the node is from
  // its contact conditions, independent of the complementarity scale.
  double
  ContactSolver::node_residual(const unsigned int j, const double p) const
  {
    if (!mortar.is_covered(j))
      return 0; // no contact possible: lambda_j = 0 by construction
    const auto &   s           = states[j];
    const auto [normal, trial] = trial_tractions(j, natural_constant(j));
    const double C_n           = s.pressure - std::max(0., normal);
    // C_t is homogeneous of degree 2 in (lambda, c u): scale it by p
    // and by the size of its trial traction.
    const double C_t =
      (mu == 0) ? s.tangential_traction * p :
                  std::max(mu * normal, std::abs(trial)) *
                      s.tangential_traction -
                    mu * std::max(0., normal) * trial;
    return std::max(std::abs(C_n) / p,
                    std::abs(C_t) / (p * std::max(p, std::abs(trial))));
  }



  // Globalisation of the active set rule when it makes no progress: the
  // rule moves every node that violates its conditions at once, and where
  // the multipliers are only weakly determined (a stiff, nearly
  // incompressible body 1 on a coarse soft body 2: stability cases 259-261)
  // the nodes' changes undo each other's. Moving only the worst nodes
  // (residual within @p fraction of the largest) lets the others follow
  // the new sets' solution. The converged sets do not depend on it: they
  // must pass the full rule unchanged.
  unsigned int
  ContactSolver::restrict_set_changes(
    const std::vector<ContactNodeState> &before,
    const double                         fraction)
  {
    const double p = largest_pressure();
    const auto   changed = [&](const unsigned int j) {
      return states[j].status != before[j].status ||
             (states[j].status == ContactStatus::slip &&
              states[j].slip_sign != before[j].slip_sign);
    };
    std::vector<double> r(states.size(), 0.);
    double              largest = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      if (changed(j))
        largest = std::max(largest, r[j] = node_residual(j, p));
    unsigned int n_kept = 0;
    for (unsigned int j = 0; j < states.size(); ++j)
      if (changed(j))
        {
          if (r[j] >= fraction * largest)
            ++n_kept;
          else
            {
              states[j].status    = before[j].status;
              states[j].slip_sign = before[j].slip_sign;
            }
        }
    return n_kept;
  }



  // Sets without a stick node leave a floating body 1 free to slide (the
  // system is singular, check_support). In a later Newton step that is
  // more often an iterate gone astray than a load beyond the friction
  // limit: the node that is nearest to sticking (smallest |trial| /
  // (mu normal)) stays in stick, and the next step decides again.
  unsigned int
  ContactSolver::keep_one_node_stuck()
  {
    const unsigned int none = states.size();
    if (mu == 0)
      return none;
    Tensor<1, 2> tangent;
    unsigned int best  = none;
    double       ratio = std::numeric_limits<double>::max();
    for (unsigned int j = 0; j < states.size(); ++j)
      {
        const auto &s = states[j];
        if (s.status == ContactStatus::stick)
          return none;
        if (s.status == ContactStatus::open)
          continue;
        tangent += s.tangent;
        const auto [normal, trial] =
          trial_tractions(j, complementarity_constant[j]);
        if (normal > 0 && std::abs(trial) / (mu * normal) < ratio)
          ratio = std::abs(trial) / (mu * normal), best = j;
      }
    if (best == none ||
        holds_translation_along(slave_support_gram, tangent / tangent.norm()))
      return none;
    states[best].status = ContactStatus::stick;
    return best;
  }



  // The complementarity residual's counterpart of multiplier_round_off:
  // normalised by the largest pressure, as the residual is.
  double
  ContactSolver::residual_round_off_floor() const
  {
    return multiplier_round_off / largest_pressure();
  }



  double
  ContactSolver::slip_increment(const unsigned int j) const
  {
    return states[j].slip - previous_weighted_slip[j] / states[j].weight;
  }



  ContactSolver::TrialTractions
  ContactSolver::trial_tractions(const unsigned int j, const double c) const
  {
    const auto &s = states[j];
    return {s.pressure - c * s.gap,
            s.tangential_traction + c * slip_increment(j)};
  }



  Tensor<1, 2>
  ContactSolver::interface_tangent() const
  {
    Tensor<1, 2> tangent;
    for (unsigned int j = 0; j < states.size(); ++j)
      if (mortar.is_covered(j))
        tangent += states[j].tangent;
    return tangent.norm() > 0 ? tangent / tangent.norm() : tangent;
  }



  double
  ContactSolver::natural_constant(const unsigned int j) const
  {
    return combined_modulus() / states[j].weight;
  }



  std::string
  ContactSolver::set_signature() const
  {
    std::string signature;
    for (const auto &s : states)
      signature += s.status == ContactStatus::open  ? 'o' :
                   s.status == ContactStatus::stick ? 't' :
                   s.slip_sign > 0                  ? '+' :
                                                      '-';
    return signature;
  }



  double
  ContactSolver::combined_modulus() const
  {
    const double E1 = slave.description().material.youngs_modulus;
    const double E2 = master.description().material.youngs_modulus;
    return E1 * E2 / (E1 + E2);
  }



  // Near null space of the combined system for AMG: the three joint rigid
  // modes of the two bodies (both rotate about the origin), and without
  // friction also body 1 sliding along the interface (its translation
  // along the mean tangent), which the frictionless contact does not
  // resist. Six modes (each body's, zero on the other) give each aggregate
  // six coarse unknowns: at 6.6e5 DoFs (blocks, mu = 0.3) the setup took
  // 1.6-1.9 s instead of 0.99 s and a GMRES iteration 82-85 instead of
  // 61-65 ms, for 25 instead of 31 iterations. Without friction the four
  // modes took 20 CG iterations and 2.8 s where the six per-body ones took
  // 22 and 3.8 s (blocks, 6.6e5 DoFs, both zeroed at the eliminated
  // components by EliminatedContactSystem::solve; the per-body modes
  // without that took 36; doc/contact.md section 2).
  std::vector<std::vector<double>>
  ContactSolver::rigid_body_modes() const
  {
    const auto modes_1 = slave.rigid_body_modes();
    const auto modes_2 = master.rigid_body_modes();
    std::vector<std::vector<double>> modes;
    for (unsigned int m = 0; m < 3; ++m)
      {
        modes.push_back(modes_1[m]);
        modes.back().insert(modes.back().end(),
                            modes_2[m].begin(),
                            modes_2[m].end());
      }
    const Tensor<1, 2> tangent = interface_tangent();
    if (mu == 0 && tangent.norm() > 0)
      {
        std::vector<double> slide(modes.front().size(), 0.);
        for (std::size_t k = 0; k < modes_1[0].size(); ++k)
          slide[k] = tangent[0] * modes_1[0][k] + tangent[1] * modes_1[1][k];
        modes.push_back(std::move(slide));
      }
    return modes;
  }



  ContactSolverReport
  ContactSolver::solve()
  {
    setup();
    // The near null space depends on the meshes only: once per load step,
    // and only for the AMG path (each Newton step evaluated both bodies'
    // modes, cell by cell, also for the direct solver, which ignores them).
    near_null_space = iterative ? rigid_body_modes() :
                                  std::vector<std::vector<double>>();

    ContactSolverReport report;
    report.frictionless = (mu == 0);
    std::vector<std::string> history = {set_signature()};
    std::vector<std::vector<unsigned int>> changed_nodes;
    unsigned int                           n_turning_steps = 0;
    // Ten-fold reductions of c when the sets cycle, at most 1e4-fold: the
    // stability sweep's case 252 (c x 1000) needs three.
    unsigned int       n_damping_steps   = 0;
    const unsigned int max_damping_steps = 4;
    // A tighter Krylov solve of converged sets (see below), at most one:
    // 1e-14 |b| is near what GMRES can reach in double precision, a second
    // one would run to the iteration limit.
    linear_tolerance_factor = 1;
    // Restricted set changes (restrict_set_changes) once the iteration
    // stalls: neither the number of changed nodes nor the residual has
    // reached a new low for four steps, and in each of the last two most
    // of the nodes the rule changes return to a status they held in an
    // earlier step of this load step (the changes undo each other). Then
    // only nodes whose residual is at least half the largest change set
    // (stability cases 259-261: 20-40 changes per step without end,
    // nearly all of them back and forth). The conditions keep the
    // restriction out of iterations that converge without it: hertz from
    // the initial gap shrinks its sets at a saturated residual without a
    // reversal; 275 reverses in every other step; 262 reaches a new low at
    // least every fourth step. Only for a body 1 that friction alone holds
    // tangentially (mu > 0, no Dirichlet data along the interface), whose
    // tangential equilibrium couples every stick/slip change to all
    // others: with body 1 held (cattaneo, a prescribed tangential
    // displacement) the sets cycle and the damping of c below converges,
    // while restricted changes drift to all-slip sets (test
    // contact_quasi_static).
    const bool restriction_allowed = [&]() {
      if (mu == 0)
        return false;
      const Tensor<1, 2> tangent = interface_tangent();
      return tangent.norm() > 0 &&
             !holds_translation_along(slave_support_gram, tangent);
    }();
    const unsigned int stagnation_window   = 4;
    const double       restricted_fraction = 0.5;
    // For each node, the statuses (bits of status_bit) of the sets that
    // Newton steps 2, 3, ... of this load step solved with; the initial or
    // predicted sets of step 1 do not count.
    std::vector<unsigned char> statuses_held(states.size(), 0);
    const auto status_bit = [](const char signature) -> unsigned char {
      return signature == 'o' ? 1 : signature == 't' ? 2 :
             signature == '+' ? 4 : 8;
    };
    bool               restricted        = false;
    unsigned int       best_changed      = std::numeric_limits<unsigned int>::max();
    double             best_residual     = std::numeric_limits<double>::max();
    unsigned int       n_stalled         = 0;
    bool               was_reversing     = false;
    // Sets without a stick node after step 1 (keep_one_node_stuck), at
    // most this many times per load step before the set changes are
    // restricted; after that, whenever it happens (an oscillating
    // iteration that moves one node at a time loses the last stick node
    // as easily as it regains it; the step limit still ends it).
    unsigned int       n_kept_stuck      = 0;
    const unsigned int max_kept_stuck    = 4;
    const auto keep_body_held = [&]() {
      if (n_kept_stuck >= max_kept_stuck && !restricted)
        return;
      const unsigned int j = keep_one_node_stuck();
      if (j < states.size())
        {
          if (!restricted)
            ++n_kept_stuck;
          pcout << "    no stick node left: the node at ("
                << states[j].position[0] << ", " << states[j].position[1]
                << "), nearest to sticking, stays in stick" << std::endl;
        }
    };

    for (unsigned int k = 1; k <= contact_parameters.max_newton_iterations;
         ++k)
      {
        if (k > 1)
          {
            const std::string sets = set_signature();
            for (unsigned int j = 0; j < sets.size(); ++j)
              statuses_held[j] |= status_bit(sets[j]);
          }
        check_support(k);
        // A free rotation makes the system singular. With a balanced load
        // it still has solutions (a disc on its first contact node, hertz
        // without 'Hold axis'), and the next step's sets decide; otherwise
        // the solve goes astray, which the diagnosis then names.
        const bool turning = slave_rotation_free();
        if (turning)
          {
            ++n_turning_steps;
            pcout << "    body 1 can turn about its active node(s) in these "
                     "sets: the system is singular"
                  << std::endl;
          }
        Timer assembly_timer;
        assemble_newton_system();
        assembly_timer.stop();
        Timer solve_timer;
        try
          {
            solve_newton_system();
          }
        catch (const SolverControl::NoConvergence &e)
          {
            throw ContactDiagnosis(
                          "Newton step " + std::to_string(k) +
                          ": the iterative linear solver did not converge (" +
                          std::to_string(e.last_step) +
                          " iterations, residual " +
                          Utilities::to_string(e.last_residual) +
                          "). Use 'Linear solver/Type = direct' for the "
                          "contact system.",
                          k);
          }
        catch (const std::exception &e)
          {
            throw ContactDiagnosis(
              "Newton step " + std::to_string(k) +
                ": the linear solve failed with these contact sets (" +
                std::to_string(report.n_active) + " active nodes). " +
                (turning ?
                   std::string("These sets and the Dirichlet data leave body "
                               "1's rotation free (a singular system): hold "
                               "the body or refine the mesh where the bodies "
                               "touch.") :
                   std::string(
                     "The most likely cause is that body 1 is not held: all "
                     "its contact nodes are open or slipping in the same "
                     "direction, and no Dirichlet data holds it (a load "
                     "beyond the friction limit, or mu = 0 without a "
                     "lateral support).")) +
                " Solver message: " + user_message(e),
              k);
          }
        solve_timer.stop();
        evaluate_contact_state();
        const std::string before    = set_signature();
        const std::vector<ContactNodeState> states_before = states;
        const unsigned int n_changed = update_sets();
        const double residual  = complementarity_residual();
        // Nodes the full rule sends back to a status held before.
        unsigned int n_reversed = 0;
        {
          const std::string proposed = set_signature();
          for (unsigned int j = 0; j < proposed.size(); ++j)
            if (proposed[j] != before[j] &&
                (statuses_held[j] & status_bit(proposed[j])) != 0)
              ++n_reversed;
        }
        const unsigned int n_moved =
          restricted && n_changed > 0 ?
            restrict_set_changes(states_before, restricted_fraction) :
            n_changed;
        if (n_changed > 0 && k > 1)
          keep_body_held();
        report.residual_history.push_back(residual);
        report.newton_iterations = k;

        std::vector<unsigned int> changed;
        const std::string after = set_signature();
        for (unsigned int j = 0; j < after.size(); ++j)
          if (after[j] != before[j])
            changed.push_back(j);
        changed_nodes.push_back(changed);

        report.n_active = report.n_stick = report.n_slip = 0;
        for (const auto &s : states)
          if (s.status != ContactStatus::open)
            {
              ++report.n_active;
              (s.status == ContactStatus::stick ? report.n_stick :
                                                  report.n_slip)++;
            }
        pcout << "    Newton " << std::setw(2) << k << ": " << std::setw(4)
              << report.n_active << " active";
        if (mu > 0)
          pcout << " (" << report.n_stick << " stick, " << report.n_slip
                << " slip)";
        pcout << ", " << n_changed << " changed";
        if (n_moved != n_changed)
          pcout << " (" << n_moved << " moved)";
        pcout << ", residual " << std::scientific
              << std::setprecision(2) << residual << std::defaultfloat
              << " (assembly " << std::setprecision(2)
              << assembly_timer.wall_time() << " s, solve "
              << solve_timer.wall_time() << " s";
        if (iterative)
          pcout << ", " << last_linear_solve.method << " "
                << last_linear_solve.n_iterations << " its"
                << (last_linear_solve.preconditioner_reused ? ", AMG reused" :
                                                               "");
        pcout << ")" << std::endl;

        // The residual cannot drop below the round-off of the multipliers,
        // which are differences of nodal forces: with a stiff, nearly
        // incompressible body 1 (E1/E2 = 1e3, nu = 0.499; stability cases
        // 118, 254, 262) that floor lies above the default tolerance.
        const double floor = residual_round_off_floor();
        report.residual_round_off_floor = floor;
        if (n_changed == 0 && residual <= std::max(contact_parameters.tolerance,
                                                   floor))
          {
            report.converged = true;
            report.slave_rotation_free = turning;
            if (turning)
              pcout << "    warning: the converged sets leave body 1's "
                       "rotation free, so its displacement is determined "
                       "only up to a small rigid rotation (stresses and "
                       "tractions do not depend on it); refine the mesh "
                       "where the bodies touch, or hold the body"
                    << std::endl;
            if (residual > contact_parameters.tolerance)
              pcout << "    residual " << residual << " is above the "
                    << "tolerance " << contact_parameters.tolerance
                    << " but within the round-off of the multipliers ("
                    << floor << "): converged" << std::endl;
            break;
          }
        // Unchanged sets above the tolerance, after a Krylov solve: the
        // multipliers are differences of nodal forces, and the Krylov
        // tolerance on |b| does not bound them node by node (hertz, 5.6e5
        // DoFs: residual 2.7e-10 after a solve to 1e-12 |b|). The same
        // system is solved again from this solution, with a 100 times
        // tighter tolerance: few iterations, and the AMG hierarchy is
        // reused since no node changed.
        if (n_changed == 0 && iterative && report.n_tighter_linear_solves == 0)
          {
            report.n_tighter_linear_solves = 1;
            linear_tolerance_factor        = 1e-2;
            pcout << "    sets unchanged, residual above the tolerance: "
                  << "the linear solve is repeated with its tolerance "
                  << "reduced to " << linear_tolerance_factor << " times"
                  << std::endl;
            continue;
          }
        // Same sets again: the next step would solve the same system.
        if (n_changed == 0)
          throw ContactDiagnosis("The contact sets have converged after " +
                               std::to_string(k) +
                               " Newton steps, but the complementarity "
                               "residual " + Utilities::to_string(residual) +
                               " stays above the tolerance " +
                               Utilities::to_string(contact_parameters.tolerance) +
                               " and above the round-off of the multipliers (" +
                               Utilities::to_string(floor) +
                               "): the linear solver is not accurate enough "
                               "for it (ill-conditioned system?). Relax "
                               "'Contact/Tolerance' or check the data.",
                               k);
        // A set configuration seen before, other than the last one: the
        // iteration cycles and will not converge.
        const auto seen = std::find(history.begin(), history.end(), after);
        // Damping: a cycle is broken by smaller c_n, c_t, which make the
        // rule move fewer nodes per step (the solution does not depend on
        // c). Quasi-static tangential steps between dissimilar bodies need
        // it: cattaneo with nu_1 = 0.1 cycles at c = E_c/D and converges at
        // 0.1 E_c/D.
        if (n_changed > 0 && seen != history.end() &&
            n_damping_steps < max_damping_steps)
          {
            ++n_damping_steps;
            for (double &c : complementarity_constant)
              c *= 0.1;
            update_sets();
            if (restricted)
              restrict_set_changes(states_before, restricted_fraction);
            if (k > 1)
              keep_body_held();
            pcout << "    the sets repeat those of step "
                  << (seen - history.begin()) << ": c_n, c_t reduced to "
                  << std::pow(0.1, n_damping_steps)
                  << " times their value (damped set changes)" << std::endl;
            history.assign(1, set_signature());
            // The damping deals with this cycle: the stall test starts
            // again (case 252: three damping steps converge; restricting
            // the changes between them cost a step).
            n_stalled     = 0;
            was_reversing = false;
            continue;
          }
        if (n_changed > 0 && seen != history.end())
          throw ContactDiagnosis("The semismooth Newton iteration cycles: after step " +
                     std::to_string(k) + " the contact sets repeat those of "
                     "step " + std::to_string(seen - history.begin()) +
                     ". Last residuals: " +
                     [&]() {
                       std::ostringstream s;
                       for (const double r : report.residual_history)
                         s << r << ' ';
                       return s.str();
                     }() +
                     "; nodes that flipped in the last step: " +
                     [&]() {
                       std::ostringstream s;
                       for (unsigned int i = 0;
                            i < std::min<std::size_t>(changed.size(), 10);
                            ++i)
                         s << '(' << states[changed[i]].position[0] << ", "
                           << states[changed[i]].position[1] << ") ";
                       return s.str();
                     }() +
                     ". c_n, c_t were reduced " +
                     std::to_string(n_damping_steps) +
                     " times ten-fold before. Try another 'Contact/"
                     "Complementarity scale'" +
                     (solver_parameters.type == "amg" ?
                        ", or 'Linear solver/Type = direct' (an inexact "
                        "iterative solve can make the sets cycle)" :
                        std::string()) +
                     ".",
                   k);
        history.push_back(after);

        const bool reversing = 2 * n_reversed > n_changed;
        if (n_changed < best_changed || residual < best_residual)
          {
            best_changed  = std::min(best_changed, n_changed);
            best_residual = std::min(best_residual, residual);
            n_stalled     = 0;
          }
        else if (++n_stalled >= stagnation_window && !restricted &&
                 reversing && was_reversing && restriction_allowed)
          {
            restricted = true;
            pcout << "    no progress in " << n_stalled
                  << " steps (changed nodes, residual), " << n_reversed
                  << " of " << n_changed
                  << " changes undo earlier ones: from now on only "
                     "the nodes with the largest violations change set"
                  << std::endl;
          }
        was_reversing = reversing;
      }

    if (!report.converged)
      {
        std::ostringstream s;
        s << "The semismooth Newton iteration did not converge in "
          << contact_parameters.max_newton_iterations
          << " steps. Residual history:";
        for (const double r : report.residual_history)
          s << ' ' << r;
        s << ". Nodes that changed set in the last step:";
        for (unsigned int i = 0;
             i < std::min<std::size_t>(changed_nodes.back().size(), 10);
             ++i)
          s << " (" << states[changed_nodes.back()[i]].position[0] << ", "
            << states[changed_nodes.back()[i]].position[1] << ")";
        if (n_turning_steps > 0)
          s << ". In " << n_turning_steps
            << " of the steps the sets and the Dirichlet data left body 1's "
               "rotation free (a single active node, or normals meeting in "
               "one point): a singular system, which the linear solver may "
               "answer with a wild iterate. Hold the body or refine the mesh "
               "where the bodies touch";
        throw ContactDiagnosis(s.str(), contact_parameters.max_newton_iterations);
      }

    for (unsigned int j = 0; j < states.size(); ++j)
      {
        states[j].slip_increment = slip_increment(j);
        previous_weighted_slip[j] = states[j].slip * states[j].weight;
      }

    for (const auto &s : states)
      {
        report.contact_force -= s.weight * (s.pressure * s.normal +
                                            s.tangential_traction * s.tangent);
        report.max_contact_pressure =
          std::max(report.max_contact_pressure, s.pressure);
      }
    return report;
  }



  const LinearSolverReport &
  ContactSolver::last_linear_solver_report() const
  {
    return last_linear_solve;
  }



  const std::vector<ContactNodeState> &
  ContactSolver::node_states() const
  {
    return states;
  }



  const MortarInterface &
  ContactSolver::mortar_interface() const
  {
    return mortar;
  }
} // namespace coulomb_adapt
