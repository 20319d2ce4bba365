#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/contact/eliminated_contact_system.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <cmath>
#include <map>

namespace coulomb_adapt
{
  namespace
  {
    // The rows of Z and Z~ that differ from the identity: an eliminated
    // component is a combination of other DoFs, with no entry of its own.
    // Per column the entries of Z and Z~, and the row's entry of u_g.
    struct EliminatedRow
    {
      std::map<types::global_dof_index, std::array<double, 2>> entries;
      double                                                   shift = 0;
    };
    using EliminatedRows = std::map<types::global_dof_index, EliminatedRow>;

    // What decides the system: (active, stick, slip sign) and (weighted
    // gap, weighted slip) of each node, compared with the last call's.
    std::pair<std::vector<std::array<int, 3>>,
              std::vector<std::array<double, 2>>>
    node_states_and_data(const std::vector<SlaveNodeConditions> &nodes)
    {
      std::vector<std::array<int, 3>>    states;
      std::vector<std::array<double, 2>> data;
      for (const SlaveNodeConditions &node : nodes)
        {
          states.push_back({{node.active,
                             node.stick,
                             node.active && !node.stick ? node.slip_sign : 0}});
          data.push_back({{node.weighted_gap, node.weighted_slip}});
        }
      return {std::move(states), std::move(data)};
    }

    // One master DoF's term in an eliminated row: its value in Z, its value
    // in the test space Z~ (0 for a DoF with Dirichlet data, which stays
    // zero in the solve: its fixed value goes into the row's shift).
    void
    add_coupling(EliminatedRow                       &row,
                 const SlaveNodeConditions::Coupling &m,
                 const unsigned int                   d,
                 const double                         value,
                 const double                         test_value,
                 bool                                &symmetric)
    {
      row.entries[m.dofs[d]] = {{value, m.constrained[d] ? 0. : test_value}};
      symmetric              = symmetric && !m.constrained[d];
      if (m.constrained[d])
        row.shift += value * m.fixed_value[d];
    }

    // A roller: the normal condition eliminates the free component, the
    // fixed one is known (its value goes into the shift), and the test
    // space is orthogonal to the traction lambda_n n, as at a
    // frictionless node: Z~ = Z.
    void
    add_roller_row(const SlaveNodeConditions &node,
                   EliminatedRows            &eliminated,
                   bool                      &symmetric)
    {
      const Tensor<1, 2> &n   = node.normal;
      const double        D   = node.weight;
      const unsigned int  o   = node.fixed_component;
      const unsigned int  c   = 1 - o;
      EliminatedRow      &row = eliminated[node.dofs[c]];
      for (const auto &m : node.couplings)
        for (unsigned int d = 0; d < 2; ++d)
          {
            const double z = m.value / D * n[d] / n[c];
            add_coupling(row, m, d, z, z, symmetric);
          }
      row.shift += (node.weighted_gap / D - n[o] * node.fixed_value) / n[c];
    }

    // Stick: both components eliminated,
    // u^1_j = (g~ n + s~ t) / D + sum_l M_jl / D u^2_l.
    void
    add_stick_rows(const SlaveNodeConditions &node,
                   EliminatedRows            &eliminated,
                   bool                      &symmetric)
    {
      const Tensor<1, 2> &n = node.normal;
      const Tensor<1, 2> &t = node.tangent;
      const double        D = node.weight;
      for (unsigned int c = 0; c < 2; ++c)
        {
          EliminatedRow &row = eliminated[node.dofs[c]];
          for (const auto &m : node.couplings)
            {
              const double z = m.value / D;
              add_coupling(row, m, c, z, z, symmetric);
            }
          row.shift +=
            (node.weighted_gap * n[c] + node.weighted_slip * t[c]) / D;
        }
    }

    // Slip: the normal condition eliminates component c, the test space
    // is orthogonal to the traction direction w = n + mu s t. c is chosen
    // so that both n_c and w_c are far from zero: one of the two
    // components always qualifies, whatever mu.
    void
    add_slip_row(const SlaveNodeConditions &node,
                 EliminatedRows            &eliminated,
                 bool                      &symmetric)
    {
      const Tensor<1, 2> &n = node.normal;
      const Tensor<1, 2> &t = node.tangent;
      const double        D = node.weight;
      const Tensor<1, 2> w = n + node.friction_coefficient * node.slip_sign * t;
      const auto         quality = [&](const unsigned int c) {
        return std::min(std::abs(n[c]), std::abs(w[c]) / w.norm());
      };
      const unsigned int c      = quality(0) >= quality(1) ? 0 : 1;
      const unsigned int o      = 1 - c;
      EliminatedRow     &row    = eliminated[node.dofs[c]];
      row.entries[node.dofs[o]] = {{-n[o] / n[c], -w[o] / w[c]}};
      for (const auto &m : node.couplings)
        for (unsigned int d = 0; d < 2; ++d)
          {
            const double z = m.value / D;
            add_coupling(
              row, m, d, z * n[d] / n[c], z * w[d] / w[c], symmetric);
          }
      row.shift += node.weighted_gap / (D * n[c]);
      symmetric = symmetric && node.friction_coefficient == 0;
    }

    // The eliminated rows of the active nodes this rank owns; @p symmetric
    // becomes false where Z~ differs from Z (on this rank).
    EliminatedRows
    eliminated_rows(const std::vector<SlaveNodeConditions> &nodes,
                    bool                                   &symmetric)
    {
      EliminatedRows eliminated;
      for (const SlaveNodeConditions &node : nodes)
        {
          if (!node.active)
            continue;
          if (node.fixed_component >= 0)
            add_roller_row(node, eliminated, symmetric);
          else if (node.stick)
            add_stick_rows(node, eliminated, symmetric);
          else
            add_slip_row(node, eliminated, symmetric);
        }
      return eliminated;
    }

    // An eliminated component has no unknown of its own, but Z keeps a
    // negligible entry on its diagonal: it puts the component's row and
    // column into the product's pattern, where the row is then replaced by
    // K's diagonal entry in place. Without it the product has no such row,
    // and a filled Epetra matrix takes no new entries: the product had to
    // be copied into a new pattern, half of the assembly at 1e6 DoFs. (An
    // explicit zero does not survive Trilinos' transposed product.) Its
    // traces elsewhere are placeholder times K, 1e-100 of K's entries,
    // and the right hand side's entry is set to zero.
    constexpr double placeholder = 1e-100;

    // The pattern of Z (and Z~): the diagonal and the eliminated rows.
    DynamicSparsityPattern
    elimination_pattern(const IndexSet &owned, const EliminatedRows &eliminated)
    {
      DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
      for (const auto i : owned)
        {
          dsp.add(i, i);
          const auto row = eliminated.find(i);
          if (row != eliminated.end())
            for (const auto &[column, value] : row->second.entries)
              dsp.add(i, column);
        }
      return dsp;
    }

    // The entries of Z, Z~ (unless symmetric) and u_g on this rank's rows:
    // the identity where nothing is eliminated.
    void
    set_elimination_entries(const IndexSet                 &owned,
                            const EliminatedRows           &eliminated,
                            const bool                      symmetric,
                            TrilinosWrappers::SparseMatrix &Z,
                            TrilinosWrappers::SparseMatrix &Z_test,
                            TrilinosWrappers::MPI::Vector  &shift)
    {
      for (const auto i : owned)
        {
          const auto row = eliminated.find(i);
          if (row == eliminated.end())
            {
              Z.set(i, i, 1.);
              if (!symmetric)
                Z_test.set(i, i, 1.);
              continue;
            }
          Z.set(i, i, placeholder);
          if (!symmetric)
            Z_test.set(i, i, placeholder);
          for (const auto &[column, value] : row->second.entries)
            {
              Z.set(i, column, value[0]);
              if (!symmetric)
                Z_test.set(i, column, value[1]);
            }
          shift(i) = row->second.shift;
        }
    }
  } // namespace



  void
  EliminatedContactSystem::reinit(const MortarInterface &,
                                  const ElasticBody       &slave,
                                  const ElasticBody       &master,
                                  const SlaveCondensation &condensation)
  {
    const auto     &K1           = slave.system_matrix();
    const auto     &K2           = master.system_matrix();
    const auto     &f1           = slave.system_rhs();
    const auto     &f2           = master.system_rhs();
    const IndexSet &owned        = condensation.owned;
    const auto      offset       = condensation.offset;
    const MPI_Comm  communicator = condensation.communicator;

    // A new load step or mesh: K may have changed, so the hierarchy is
    // rebuilt; u of the last solve stays the initial guess on the same
    // index space (the previous load step's solution).
    amg.reset();
    amg_matrix.reset();
    reduced.reset();
    if (owned != this->owned)
      last_solution.clear();
    this->owned        = owned;
    this->communicator = communicator;

    DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
    for (const auto row : K1.locally_owned_range_indices())
      for_each_entry(K1, row, [&](const auto column, const double) {
        dsp.add(row, column);
      });
    for (const auto row : K2.locally_owned_range_indices())
      for_each_entry(K2, row, [&](const auto column, const double) {
        dsp.add(offset + row, offset + column);
      });
    stiffness.reinit(owned, owned, dsp, communicator);

    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    const auto copy_rows = [&](const TrilinosWrappers::SparseMatrix &K,
                               const types::global_dof_index         shift) {
      for (const auto row : K.locally_owned_range_indices())
        {
          columns.clear();
          values.clear();
          for_each_entry(K, row, [&](const auto column, const double value) {
            columns.push_back(shift + column);
            values.push_back(value);
          });
          stiffness.set(shift + row,
                        columns.size(),
                        columns.data(),
                        values.data());
        }
    };
    copy_rows(K1, 0);
    copy_rows(K2, offset);
    stiffness.compress(VectorOperation::insert);

    load.reinit(owned, communicator);
    for (const auto i : f1.locally_owned_elements())
      load(i) = f1(i);
    for (const auto i : f2.locally_owned_elements())
      load(offset + i) = f2(i);
    load.compress(VectorOperation::insert);
  }



  void
  EliminatedContactSystem::assemble(
    const std::vector<SlaveNodeConditions> &nodes)
  {
    // The same sets and data as the last call (a repeated solve of
    // converged sets, ContactSolver::solve): the system is built already.
    auto [states, data] = node_states_and_data(nodes);
    const bool unchanged =
      reduced && states == node_states && data == node_data;
    if (Utilities::MPI::min(unchanged ? 1 : 0, communicator) == 1)
      return;
    node_states = std::move(states);
    node_data   = std::move(data);
    // The last step's matrix is not needed any more unless the AMG
    // hierarchy was built from it (amg_matrix keeps it then): freed before
    // the products below build the next one.
    reduced.reset();

    symmetric                       = true;
    const EliminatedRows eliminated = eliminated_rows(nodes, symmetric);
    symmetric = Utilities::MPI::min(symmetric ? 1 : 0, communicator) == 1;

    const DynamicSparsityPattern dsp = elimination_pattern(owned, eliminated);
    // A symmetric system has Z~ = Z: built once.
    TrilinosWrappers::SparseMatrix        Z_test_storage;
    const TrilinosWrappers::SparseMatrix &Z_test =
      symmetric ? Z : Z_test_storage;
    Z.reinit(owned, owned, dsp, communicator);
    if (!symmetric)
      Z_test_storage.reinit(owned, owned, dsp, communicator);
    shift.reinit(owned, communicator);
    set_elimination_entries(
      owned, eliminated, symmetric, Z, Z_test_storage, shift);
    Z.compress(VectorOperation::insert);
    if (!symmetric)
      Z_test_storage.compress(VectorOperation::insert);
    shift.compress(VectorOperation::insert);

    TrilinosWrappers::SparseMatrix KZ;
    stiffness.mmult(KZ, Z);
    reduced = std::make_shared<TrilinosWrappers::SparseMatrix>();
    Z_test.Tmmult(*reduced, KZ);
    // The rows of eliminated components: decoupled, with K's diagonal
    // entry, so that the operator keeps the scale AMG's smoother expects.
    eliminated_dofs.clear();
    for (const auto &[i, row] : eliminated)
      eliminated_dofs.push_back(i);
    reduced->clear_rows(eliminated_dofs);
    for (const auto i : eliminated_dofs)
      reduced->set(i, i, stiffness.diag_element(i));
    reduced->compress(VectorOperation::insert);

    TrilinosWrappers::MPI::Vector residual(owned, communicator);
    stiffness.vmult(residual, shift);
    residual.sadd(-1., 1., load);
    reduced_rhs.reinit(owned, communicator);
    Z_test.Tvmult(reduced_rhs, residual);
    for (const auto i : eliminated_dofs)
      reduced_rhs(i) = 0.;
    reduced_rhs.compress(VectorOperation::insert);
  }



  // Initial guess: the last u on the components that stay unknowns; an
  // eliminated component's reduced unknown is zero (decoupled row, zero
  // right hand side).
  TrilinosWrappers::MPI::Vector
  EliminatedContactSystem::initial_reduced_guess() const
  {
    TrilinosWrappers::MPI::Vector reduced_solution(owned, communicator);
    if (last_solution.size() == owned.size())
      {
        reduced_solution = last_solution;
        for (const auto i : eliminated_dofs)
          reduced_solution(i) = 0.;
        reduced_solution.compress(VectorOperation::insert);
      }
    return reduced_solution;
  }



  bool
  EliminatedContactSystem::hierarchy_may_be_reused() const
  {
    if (!(amg && states_at_build.size() == node_states.size() &&
          last_iterations <= fresh_iterations * 3 / 2 + 5))
      return false;
    unsigned int n_changed = 0;
    for (unsigned int j = 0; j < node_states.size(); ++j)
      n_changed += (node_states[j] != states_at_build[j]);
    n_changed = Utilities::MPI::sum(n_changed, communicator);
    return n_changed <= max_changed_nodes_for_reuse;
  }



  LinearSolverReport
  EliminatedContactSystem::solve_with_current_hierarchy(
    const parameters::LinearSolver &settings,
    TrilinosWrappers::MPI::Vector  &reduced_solution)
  {
    parameters::LinearSolver capped = settings;
    capped.max_iterations =
      std::min(settings.max_iterations, 2 * fresh_iterations + 10);
    LinearSolverReport report    = solve_krylov(*reduced,
                                             reduced_solution,
                                             reduced_rhs,
                                             amg->preconditioner,
                                             capped,
                                             symmetric);
    report.preconditioner_reused = true;
    return report;
  }



  LinearSolverReport
  EliminatedContactSystem::solve_with_fresh_hierarchy(
    const std::vector<std::vector<double>> &near_null_space,
    const parameters::LinearSolver         &settings,
    const TrilinosWrappers::MPI::Vector    &initial_guess,
    TrilinosWrappers::MPI::Vector          &reduced_solution)
  {
    // The modes are zero at the eliminated components: their rows are
    // decoupled (K's diagonal, zero right hand side), so a mode with an
    // entry there is no near null vector of the reduced operator, and
    // the Krylov solves need more iterations (doc/contact.md section 2).
    std::vector<std::vector<double>> modes = near_null_space;
    for (auto &mode : modes)
      for (const auto i : eliminated_dofs)
        if (owned.is_element(i))
          mode[owned.index_within_set(i)] = 0.;
    amg.reset();
    amg = std::make_unique<ElasticityAMG>();
    amg->initialize(*reduced, modes);
    amg_matrix                = reduced;
    states_at_build           = node_states;
    reduced_solution          = initial_guess;
    LinearSolverReport report = solve_krylov(*reduced,
                                             reduced_solution,
                                             reduced_rhs,
                                             amg->preconditioner,
                                             settings,
                                             symmetric);
    fresh_iterations          = report.n_iterations;
    return report;
  }



  // The previous hierarchy is reused when few slave nodes changed set
  // since it was built, and while it still needs few iterations. Its
  // attempt is capped, and a failed one is repeated with a fresh
  // hierarchy, so a poor guess costs a few iterations, not the solve.
  LinearSolverReport
  EliminatedContactSystem::solve(
    const std::vector<std::vector<double>> &near_null_space,
    const parameters::LinearSolver         &settings,
    TrilinosWrappers::MPI::Vector          &solution)
  {
    TrilinosWrappers::MPI::Vector reduced_solution    = initial_reduced_guess();
    const TrilinosWrappers::MPI::Vector initial_guess = reduced_solution;

    LinearSolverReport report;
    if (hierarchy_may_be_reused())
      try
        {
          report = solve_with_current_hierarchy(settings, reduced_solution);
        }
      catch (const SolverControl::NoConvergence &)
        {
          report = solve_with_fresh_hierarchy(near_null_space,
                                              settings,
                                              initial_guess,
                                              reduced_solution);
        }
    else
      report = solve_with_fresh_hierarchy(near_null_space,
                                          settings,
                                          initial_guess,
                                          reduced_solution);
    last_iterations = report.n_iterations;

    solution.reinit(owned, communicator);
    Z.vmult(solution, reduced_solution);
    solution += shift;
    last_solution = solution;
    return report;
  }
} // namespace coulomb_adapt
