#include <deal.II/base/mpi.h>

#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/contact/eliminated_contact_system.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace coulomb_adapt
{
  namespace
  {
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

    // Whether two steps eliminate the same components with the same rows
    // of Z and Z~ (u_g aside): with K unchanged, A = Z~^T K Z is then the
    // same matrix.
    bool
    same_elimination(const EliminatedRows &a, const EliminatedRows &b)
    {
      return a.size() == b.size() &&
             std::equal(a.begin(),
                        a.end(),
                        b.begin(),
                        [](const auto &row_a, const auto &row_b) {
                          return row_a.first == row_b.first &&
                                 row_a.second.entries == row_b.second.entries;
                        });
    }

    // An eliminated component has no unknown of its own, but Z keeps a
    // negligible entry on its diagonal: the reduced matrix has the
    // component's row (which then holds K's diagonal entry only) and
    // column in its pattern, with placeholder times K's entries elsewhere
    // in them, 1e-100 of K's. The matrix is thereby the one the earlier
    // construction with Trilinos' matrix products gave, entry for entry
    // and with the same pattern (benchmarks/adaptive_run, "Memory"), and
    // so are the AMG hierarchy and the solution. The right hand side's
    // entry is zero.
    constexpr double placeholder = 1e-100;
  } // namespace



  void
  EliminatedContactSystem::reinit(const MortarInterface &,
                                  const ElasticBody       &slave,
                                  const ElasticBody       &master,
                                  const SlaveCondensation &condensation)
  {
    // A new load step or mesh: K may have changed, so the hierarchy is
    // rebuilt; u of the last solve stays the initial guess on the same
    // index space (the previous load step's solution).
    amg.reset();
    amg_matrix.reset();
    reduced.reset();
    if (condensation.owned != owned)
      last_solution.clear();
    owned        = condensation.owned;
    communicator = condensation.communicator;
    offset       = condensation.offset;
    K1           = &slave.system_matrix();
    K2           = &master.system_matrix();
    f1           = &slave.system_rhs();
    f2           = &master.system_rhs();
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

    bool           step_symmetric = true;
    EliminatedRows rows           = eliminated_rows(nodes, step_symmetric);
    // The same sets with other gaps or slips (typically the last Newton
    // step, which confirms the sets): only u_g and with it b change, A is
    // the last step's. Building it again would hold two copies of it
    // while a reused AMG hierarchy keeps the old one.
    const bool same_matrix =
      Utilities::MPI::min(reduced && same_elimination(rows, eliminated) ? 1 : 0,
                          communicator) == 1;
    eliminated = std::move(rows);
    symmetric  = Utilities::MPI::min(step_symmetric ? 1 : 0, communicator) == 1;
    eliminated_dofs.clear();
    for (const auto &[i, row] : eliminated)
      eliminated_dofs.push_back(i);

    const EliminatedOperator product(
      *K1, *K2, *f1, *f2, offset, owned, communicator, eliminated, placeholder);
    if (!same_matrix)
      {
        // The last step's matrix is not needed any more unless the AMG
        // hierarchy was built from it (amg_matrix keeps it then): freed
        // before the next one is built.
        reduced.reset();
        reduced = product.reduced_operator();
      }
    product.reduced_rhs(reduced_rhs);
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
    amg.reset();
    amg = std::make_unique<ElasticityAMG>();
    initialize_elasticity_amg(*amg, *reduced, near_null_space, eliminated_dofs);
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

    EliminatedOperator::expand(eliminated,
                               placeholder,
                               reduced_solution,
                               solution);
    last_solution = solution;
    return report;
  }
} // namespace coulomb_adapt
