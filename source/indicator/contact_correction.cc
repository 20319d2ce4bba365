#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/indicator/bernstein_contact_traction.h>
#include <coulomb_adapt/indicator/contact_correction.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <algorithm>
#include <cmath>

namespace coulomb_adapt
{
  std::array<double, 2>
  project_onto_coulomb_cone(const double lambda_n,
                            const double lambda_t,
                            const double mu)
  {
    if (std::abs(lambda_t) <= mu * lambda_n)
      return {{lambda_n, lambda_t}};
    // In the polar cone: the nearest point of K_mu is its apex.
    if (mu * std::abs(lambda_t) <= -lambda_n)
      return {{0., 0.}};
    // Otherwise onto the nearest edge of the cone, the ray (1, mu s).
    const double n = (lambda_n + mu * std::abs(lambda_t)) / (1 + mu * mu);
    return {{n, mu * std::copysign(n, lambda_t)}};
  }



  namespace
  {
    // The rigid motions body @p body can make without moving its supported
    // (Dirichlet or point-constrained) DoFs: the null space of the
    // Gram matrix of the rigid modes restricted to those DoFs. Modes are
    // the translations and the rotation about the body's centre, scaled to
    // O(1) entries so that one threshold fits every body.
    std::vector<TrilinosWrappers::MPI::Vector>
    free_rigid_modes(const ElasticBody &body)
    {
      const MPI_Comm comm  = body.triangulation().get_communicator();
      const auto    &owned = body.locally_owned_dof_set();

      Point<2> lower(1e300, 1e300), upper(-1e300, -1e300);
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < 2; ++d)
              {
                lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                upper[d] = std::max(upper[d], cell->vertex(v)[d]);
              }
      for (unsigned int d = 0; d < 2; ++d)
        {
          lower[d] = Utilities::MPI::min(lower[d], comm);
          upper[d] = Utilities::MPI::max(upper[d], comm);
        }
      const Point<2> centre = (lower + upper) / 2;
      const double   radius = (upper - lower).norm() / 2;

      // rigid_body_modes(): x, y translation and rotation about the origin.
      auto modes = body.rigid_body_modes();
      for (unsigned int k = 0; k < modes[2].size(); ++k)
        modes[2][k] =
          (modes[2][k] + centre[1] * modes[0][k] - centre[0] * modes[1][k]) /
          radius;

      const auto &constraints  = body.constraints();
      auto        is_supported = [&](const types::global_dof_index i) {
        return constraints.is_constrained(i) &&
               constraints.get_constraint_entries(i)->empty();
      };
      SymmetricTensor<2, 3> gram;
      unsigned int          k = 0;
      for (const auto i : owned)
        {
          if (is_supported(i))
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = a; b < 3; ++b)
                gram[a][b] += modes[a][k] * modes[b][k];
          ++k;
        }
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = a; b < 3; ++b)
          gram[a][b] = Utilities::MPI::sum(gram[a][b], comm);

      std::vector<TrilinosWrappers::MPI::Vector> free;
      for (const auto &[value, direction] : eigenvectors(gram))
        if (value < 1e-8)
          {
            TrilinosWrappers::MPI::Vector z(owned, comm);
            unsigned int                  k = 0;
            for (const auto i : owned)
              {
                if (!constraints.is_constrained(i))
                  z(i) = direction[0] * modes[0][k] +
                         direction[1] * modes[1][k] +
                         direction[2] * modes[2][k];
                ++k;
              }
            z.compress(VectorOperation::insert);
            free.push_back(z);
          }
      return free;
    }



    // DoFs that fix the free rigid modes when pinned: Gaussian elimination
    // with complete pivoting on the (n_dofs x n_modes) matrix of the modes.
    std::vector<types::global_dof_index>
    pinning_dofs(const std::vector<TrilinosWrappers::MPI::Vector> &modes,
                 const MPI_Comm                                    comm)
    {
      std::vector<TrilinosWrappers::MPI::Vector> reduced = modes;
      std::vector<types::global_dof_index>       pinned;
      for (unsigned int m = 0; m < reduced.size(); ++m)
        {
          // The largest remaining entry of mode m, over all ranks.
          double                  best  = 0;
          types::global_dof_index where = 0;
          for (const auto i : reduced[m].locally_owned_elements())
            if (std::abs(reduced[m](i)) > best)
              {
                best  = std::abs(reduced[m](i));
                where = i;
              }
          const auto candidates =
            Utilities::MPI::all_gather(comm, std::make_pair(best, where));
          const auto pick = *std::max_element(candidates.begin(),
                                              candidates.end(),
                                              [](const auto &a, const auto &b) {
                                                return a.first < b.first;
                                              });
          pinned.push_back(pick.second);

          // Every mode's value at the pinned DoF, from its owner.
          std::vector<double> local;
          if (reduced[m].locally_owned_elements().is_element(pick.second))
            for (const auto &r : reduced)
              local.push_back(r(pick.second));
          std::vector<double> at_pick;
          for (const auto &v : Utilities::MPI::all_gather(comm, local))
            if (!v.empty())
              at_pick = v;
          // Eliminate the pinned DoF from the remaining modes.
          for (unsigned int r = m + 1; r < reduced.size(); ++r)
            reduced[r].add(-at_pick[r] / at_pick[m], reduced[m]);
        }
      return pinned;
    }



    // The projection v <- v - Z G^-1 Z^T v onto the complement of the
    // free modes Z (G = Z^T Z their Gram matrix): no free-mode component
    // left in v.
    class FreeModeRemoval
    {
    public:
      explicit FreeModeRemoval(
        const std::vector<TrilinosWrappers::MPI::Vector> &modes)
        : modes(modes)
        , inverse(modes.size(), modes.size())
      {
        const unsigned int n = modes.size();
        FullMatrix<double> gram(n, n);
        for (unsigned int a = 0; a < n; ++a)
          for (unsigned int b = 0; b < n; ++b)
            gram(a, b) = modes[a] * modes[b];
        if (n > 0)
          inverse.invert(gram);
      }

      void
      operator()(TrilinosWrappers::MPI::Vector &v) const
      {
        const unsigned int  n = modes.size();
        std::vector<double> projections(n);
        for (unsigned int a = 0; a < n; ++a)
          projections[a] = modes[a] * v;
        for (unsigned int a = 0; a < n; ++a)
          {
            double coefficient = 0;
            for (unsigned int b = 0; b < n; ++b)
              coefficient += inverse(a, b) * projections[b];
            v.add(-coefficient, modes[a]);
          }
      }

    private:
      const std::vector<TrilinosWrappers::MPI::Vector> &modes;
      FullMatrix<double>                                inverse;
    };



    // Solve K increment = residual with the free rigid modes @p modes
    // pinned at DoFs that fix them. The pinned rows keep the size of K's
    // diagonal, which AMG's smoother expects.
    void
    solve_pinned(const ElasticBody                                &body,
                 const std::vector<TrilinosWrappers::MPI::Vector> &modes,
                 TrilinosWrappers::MPI::Vector                    &residual,
                 TrilinosWrappers::MPI::Vector                    &increment,
                 const parameters::LinearSolver &solver_parameters)
    {
      const MPI_Comm comm     = body.triangulation().get_communicator();
      const auto    &owned    = body.locally_owned_dof_set();
      const auto    &K        = body.system_matrix();
      const auto     pinned   = pinning_dofs(modes, comm);
      double         diagonal = 0;
      for (const auto i : pinned)
        if (owned.is_element(i))
          diagonal = std::max(diagonal, K.diag_element(i));
      diagonal = Utilities::MPI::max(diagonal, comm);
      TrilinosWrappers::SparseMatrix pinned_matrix;
      pinned_matrix.copy_from(K);
      pinned_matrix.clear_rows(pinned, diagonal);
      for (const auto i : pinned)
        if (owned.is_element(i))
          residual(i) = 0;
      residual.compress(VectorOperation::insert);
      solve_linear_system(pinned_matrix,
                          increment,
                          residual,
                          body.rigid_body_modes(),
                          solver_parameters,
                          false);
    }



    // Solve K u = f for a body, pinning its free rigid modes if it has
    // any; the result satisfies the body's constraints and, for a floating
    // body, u - u_reference is orthogonal to the free modes.
    //
    // What is solved for is the increment u - u_reference, u_reference
    // being the FE solution: the correction is small, and a solver's
    // relative accuracy then applies to it, not to u. Solving for u
    // itself, an iterative solve of the pinned system of a floating body
    // (conditioned by the pin) left errors of 17 % of u (hertz, 5.6e5
    // DoFs, a correction of 7e-12: epsilon 71 % instead of 1 %).
    TrilinosWrappers::MPI::Vector
    solve_under_prescribed_tractions(
      const ElasticBody                   &body,
      const TrilinosWrappers::MPI::Vector &load,
      const TrilinosWrappers::MPI::Vector &u_reference,
      const parameters::LinearSolver      &solver_parameters)
    {
      const MPI_Comm        comm  = body.triangulation().get_communicator();
      const auto           &owned = body.locally_owned_dof_set();
      const auto            modes = free_rigid_modes(body);
      const auto           &K     = body.system_matrix();
      const FreeModeRemoval remove_modes(modes);

      // The increment's load f - K u_reference, zero in constrained rows
      // (the constraints are imposed on u below). For a floating body, the
      // resultant on the free modes cannot be balanced: remove it (the l2
      // projection onto the range of K).
      TrilinosWrappers::MPI::Vector reference(owned, comm);
      reference = u_reference;
      TrilinosWrappers::MPI::Vector residual(owned, comm);
      K.vmult(residual, reference);
      residual.sadd(-1., 1., load);
      for (const auto i : owned)
        if (body.constraints().is_constrained(i))
          residual(i) = 0;
      residual.compress(VectorOperation::insert);
      remove_modes(residual);

      TrilinosWrappers::MPI::Vector increment(owned, comm);
      try
        {
          if (modes.empty())
            solve_linear_system(K,
                                increment,
                                residual,
                                body.rigid_body_modes(),
                                solver_parameters);
          else
            solve_pinned(body, modes, residual, increment, solver_parameters);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          // deal.II's text names neither the body, nor the phase, nor the
          // parameter.
          AssertThrow(false,
                      ExcMessage(iteration_limit_message(
                        "body '" + body.name() +
                          "', the error indicator's corrected problem (the "
                          "body under the contact tractions projected onto "
                          "the Coulomb cone)",
                        "",
                        e.last_step,
                        e.last_residual)));
        }
      // No free-mode component in u - u_reference. Removed before the
      // constraints are distributed: the free modes vanish at constrained
      // DoFs, so removed afterwards a mode's hanging-node entries would
      // stay behind (and differ with the solver's choice of the mode's
      // multiple).
      remove_modes(increment);
      TrilinosWrappers::MPI::Vector solution(reference);
      solution += increment;
      body.constraints().distribute(solution);
      return solution;
    }
  } // namespace



  std::vector<Tensor<1, 2>>
  contact_traction_at(const MortarInterface                            &mortar,
                      const std::vector<ContactNodeFields>             &fields,
                      const std::vector<MortarInterface::OverlapPoint> &points)
  {
    const auto               &nodes    = mortar.slave_nodes();
    const auto               &segments = mortar.slave_segment_list();
    std::vector<Tensor<1, 2>> traction(points.size());
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const auto &segment =
          segments[mortar.overlaps()[points[q].overlap].slave_segment];
        // Bernstein's basis keeps R in the cone between the nodes, on
        // quadratic segments too (their Lagrange interpolant overshoots
        // where the zone opens: a negative pressure, which the CRE bound
        // cannot take).
        const auto phi = mortar.slave_bernstein_values(points[q].xi);
        for (unsigned int k = 0; k < segment.nodes.size(); ++k)
          {
            const auto &node = nodes[segment.nodes[k]];
            const auto &f    = fields[segment.nodes[k]];
            traction[q] -= phi[k] * (f.pressure * node.normal +
                                     f.tangential_traction * node.tangent);
          }
      }
    return traction;
  }



  unsigned int
  contact_traction_points_per_overlap(const unsigned int degree)
  {
    return degree + 3;
  }



  CorrectedContactSolution
  correct_contact_solution(const ElasticBody              &slave,
                           const ElasticBody              &master,
                           const ContactSolution          &contact,
                           const double                    mu,
                           const parameters::LinearSolver &solver_parameters,
                           const ContactLoadForm           load_form)
  {
    return correct_contact_solution(slave,
                                    master,
                                    contact.mortar_interface(),
                                    contact.node_states(),
                                    mu,
                                    solver_parameters,
                                    load_form,
                                    contact.accepted_residual());
  }



  namespace
  {
    // R_c: the nodal reactions projected onto the Coulomb cone, into
    // corrected.fields with the FE gaps and slips; the number of projected
    // nodes and the relative change. Changes at the level of the
    // condensation's round-off are not corrections. Returns the largest
    // nodal reaction.
    double
    project_reactions(const MortarInterface               &mortar,
                      const std::vector<ContactNodeState> &states,
                      const double                         mu,
                      CorrectedContactSolution            &corrected)
    {
      const auto &nodes = mortar.slave_nodes();
      const auto &D     = mortar.slave_weights();

      double largest = 0;
      for (const auto &s : states)
        largest = std::max(
          {largest, std::abs(s.pressure), std::abs(s.tangential_traction)});
      std::vector<Tensor<1, 2>> change(states.size());
      double                    change_norm = 0, norm = 0;
      for (unsigned int j = 0; j < states.size(); ++j)
        {
          const auto &s = states[j];
          const auto  projected =
            project_onto_coulomb_cone(s.pressure, s.tangential_traction, mu);
          const double dn = projected[0] - s.pressure;
          const double dt = projected[1] - s.tangential_traction;
          if (std::abs(dn) + std::abs(dt) > 1e-10 * largest)
            {
              ++corrected.n_projected_nodes;
              change[j] = dn * nodes[j].normal + dt * nodes[j].tangent;
              corrected.largest_nodal_change =
                std::max(corrected.largest_nodal_change,
                         change[j].norm() / largest);
            }
          corrected.fields[j].pressure            = projected[0];
          corrected.fields[j].tangential_traction = projected[1];
          corrected.fields[j].gap                 = s.gap;
          // The incremental law's slip: W_t of this load step.
          corrected.fields[j].slip = s.slip_increment;
          change_norm += D[j] * change[j].norm_square();
          norm += D[j] * (s.pressure * s.pressure +
                          s.tangential_traction * s.tangential_traction);
        }
      corrected.relative_change = norm > 0 ? std::sqrt(change_norm / norm) : 0.;
      return largest;
    }



    // The contact loads of the corrected problem: f^1 - D lambda_c on body
    // 1, f^2 + M^T lambda_c on body 2 (the FE solution satisfies the same
    // equations with lambda_h), in the mortar or the consistent form.
    class CorrectedLoads
    {
    public:
      CorrectedLoads(const ElasticBody     &slave,
                     const ElasticBody     &master,
                     const MortarInterface &mortar)
        : bodies{{&slave, &master}}
        , loads{{slave.system_rhs(), master.system_rhs()}}
        , mortar(mortar)
      {}

      // -D_jj lambda_j at slave node j, M_jl lambda_j at master node l.
      void
      add_mortar_form(const std::vector<ContactNodeFields> &fields)
      {
        const auto &nodes        = mortar.slave_nodes();
        const auto &D            = mortar.slave_weights();
        const auto &master_nodes = mortar.master_nodes();
        const auto &M            = mortar.master_coupling();
        for (unsigned int j = 0; j < fields.size(); ++j)
          {
            const Tensor<1, 2> lambda =
              fields[j].pressure * nodes[j].normal +
              fields[j].tangential_traction * nodes[j].tangent;
            add(0, nodes[j].dofs, -D[j] * lambda);
            for (const auto &[l, m] : M[j])
              add(1, master_nodes[l].dofs, m * lambda);
          }
      }

      // int R phi_k on the slave side, -int R phi^2_l on the master side:
      // the same traction field, integrated where the bodies face each
      // other (R vanishes elsewhere, since a node with a nonzero reaction
      // has its whole support covered).
      void
      add_consistent_form(const std::vector<ContactNodeFields> &fields)
      {
        const auto &nodes        = mortar.slave_nodes();
        const auto &master_nodes = mortar.master_nodes();
        const auto  points       = mortar.overlap_quadrature(
          contact_traction_points_per_overlap(mortar.slave_element_degree()));
        const auto  R = contact_traction_at(mortar, fields, points);
        const auto &slave_segments  = mortar.slave_segment_list();
        const auto &master_segments = mortar.master_segment_list();
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const auto &overlap = mortar.overlaps()[points[q].overlap];
            const auto &s_nodes = slave_segments[overlap.slave_segment].nodes;
            const auto &m_nodes = master_segments[overlap.master_segment].nodes;
            const auto  phi_s   = mortar.slave_shape_values(points[q].xi);
            const auto  phi_m   = mortar.master_shape_values(points[q].eta);
            for (unsigned int k = 0; k < s_nodes.size(); ++k)
              add(0,
                  nodes[s_nodes[k]].dofs,
                  phi_s[k] * points[q].weight * R[q]);
            for (unsigned int k = 0; k < m_nodes.size(); ++k)
              add(1,
                  master_nodes[m_nodes[k]].dofs,
                  -phi_m[k] * points[q].weight * R[q]);
          }
      }

      const std::array<const ElasticBody *, 2>     bodies;
      std::array<TrilinosWrappers::MPI::Vector, 2> loads;

    private:
      // A nodal force, at the DoFs body @p b owns and does not constrain.
      void
      add(const unsigned int                            b,
          const std::array<types::global_dof_index, 2> &dofs,
          const Tensor<1, 2>                           &force)
      {
        for (unsigned int c = 0; c < 2; ++c)
          if (bodies[b]->locally_owned_dof_set().is_element(dofs[c]) &&
              !bodies[b]->constraints().is_constrained(dofs[c]))
            loads[b](dofs[c]) += force[c];
      }

      const MortarInterface &mortar;
    };



    // The displacements of both bodies under the corrected contact loads,
    // and W_c from them, measured as the solver measures its iterates.
    void
    solve_corrected_problem(const ElasticBody                   &slave,
                            const ElasticBody                   &master,
                            const MortarInterface               &mortar,
                            const std::vector<ContactNodeState> &states,
                            const parameters::LinearSolver &solver_parameters,
                            const ContactLoadForm           load_form,
                            CorrectedContactSolution       &corrected)
    {
      CorrectedLoads corrected_loads(slave, master, mortar);
      if (load_form == ContactLoadForm::mortar)
        corrected_loads.add_mortar_form(corrected.fields);
      else
        corrected_loads.add_consistent_form(corrected.fields);
      for (unsigned int b = 0; b < 2; ++b)
        {
          const ElasticBody             &body = *corrected_loads.bodies[b];
          TrilinosWrappers::MPI::Vector &load = corrected_loads.loads[b];
          load.compress(VectorOperation::add);
          const TrilinosWrappers::MPI::Vector solution =
            solve_under_prescribed_tractions(body,
                                             load,
                                             body.solution(),
                                             solver_parameters);
          // With the ghost entries: the estimators read each owned cell's
          // DoFs, some of which other ranks own. Without them (a copy of
          // the owned entries, as before) a Trilinos vector read there
          // gave whatever lay in memory: on 2 ranks, hertz Q2 had
          // epsilon = 34 % instead of 1.09 %.
          TrilinosWrappers::MPI::Vector &stored =
            corrected.corrected_displacement[b];
          stored.reinit(body.locally_owned_dof_set(),
                        body.locally_relevant_dof_set(),
                        body.triangulation().get_communicator());
          stored = solution;
        }

      const auto gaps =
        mortar.nodal_gaps(corrected.displacement(0), corrected.displacement(1));
      for (unsigned int j = 0; j < mortar.slave_nodes().size(); ++j)
        if (mortar.is_covered(j))
          {
            corrected.fields[j].gap = gaps[j].gap;
            corrected.fields[j].slip =
              gaps[j].slip - (states[j].slip - states[j].slip_increment);
          }
    }



    // Penetration at the level of round-off of the displacements is none.
    double
    max_penetration(const std::vector<ContactNodeFields> &fields)
    {
      double scale = 0;
      for (const auto &f : fields)
        scale = std::max({scale, std::abs(f.gap), std::abs(f.slip)});
      double penetration = 0;
      for (const auto &f : fields)
        if (-f.gap > 1e-10 * scale)
          penetration = std::max(penetration, -f.gap);
      return penetration;
    }
  } // namespace



  CorrectedContactSolution
  correct_contact_solution(const ElasticBody                   &slave,
                           const ElasticBody                   &master,
                           const MortarInterface               &mortar,
                           const std::vector<ContactNodeState> &states,
                           const double                         mu,
                           const parameters::LinearSolver &solver_parameters,
                           const ContactLoadForm           load_form,
                           const double                    negligible_change)
  {
    CorrectedContactSolution corrected;
    corrected.fields.resize(states.size());
    corrected.fe_displacement = {{&slave.solution(), &master.solution()}};

    const double largest = project_reactions(mortar, states, mu, corrected);
    corrected.within_solve_accuracy =
      corrected.n_projected_nodes > 0 &&
      corrected.relative_change <= negligible_change;
    corrected.skipped =
      (corrected.n_projected_nodes == 0) || corrected.within_solve_accuracy;
    // The consistent load differs from the mortar load the FE solution
    // balances whenever there is any contact traction at all.
    if (load_form == ContactLoadForm::consistent)
      {
        corrected.skipped               = (largest == 0);
        corrected.within_solve_accuracy = false;
        // From here on the tractions are coefficients in the Bernstein
        // basis (contact_traction_at()), in the cone between the nodes.
        auto traction =
          bernstein_contact_traction(mortar, corrected.fields, mu);
        corrected.fields = std::move(traction.coefficients);
        if (mortar.slave_element_degree() > 1)
          corrected.bernstein = traction.report;
      }

    if (!corrected.skipped)
      solve_corrected_problem(
        slave, master, mortar, states, solver_parameters, load_form, corrected);
    corrected.max_penetration = max_penetration(corrected.fields);
    return corrected;
  }
} // namespace coulomb_adapt
