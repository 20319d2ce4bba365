#include <deal.II/base/work_stream.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <coulomb_adapt/indicator/equilibration_mesh.h>

#include <algorithm>
#include <memory>

namespace coulomb_adapt
{
  namespace equilibration
  {
    namespace
    {
      // Where a cell's quadratic form (see optimise_free_parameters())
      // sits in the flat arrays: n parameter names, then H packed by rows
      // of its lower triangle, g and t, n each.
      struct CellForm
      {
        unsigned int active_cell_index = 0;
        unsigned int n                 = 0;
        std::size_t  names_offset      = 0;
        std::size_t  data_offset       = 0;
        double       c                 = 0;
        double       t0                = 0;
      };

      // What one thread needs for a cell: its own local problem and
      // scratch vectors.
      struct CellScratch
      {
        CellScratch(const LocalNeumannProblem &prototype,
                    const unsigned int         n_name_dofs)
          : local(prototype)
          , load(prototype.n_coefficients())
          , name_dofs(n_name_dofs)
        {}

        LocalNeumannProblem                  local;
        Vector<double>                       load, base_whitened;
        std::vector<types::global_dof_index> name_dofs, direction_dofs;
        std::vector<Vector<double>>          direction_loads, whitened;
        FullMatrix<double>                   W;
      };

      // What a cell adds: its quadratic form (H and g also for the global
      // system), the names of its parameters, and where they act on the
      // faces ([face, node, component] and [face, component]).
      struct CellCopy
      {
        CellForm                                  form;
        double                                    defect = 0;
        std::vector<types::global_dof_index>      names;
        FullMatrix<double>                        H;
        std::vector<double>                       g, packed;
        std::vector<std::array<unsigned int, 3>>  node_names;
        std::vector<types::global_dof_index>      node_name_dofs;
        std::vector<std::array<unsigned int, 2>>  bubble_names;
        std::vector<types::global_dof_index>      bubble_name_dofs;
      };
    } // namespace



    // Step 5 of equilibrated_stress_errors(): the free parameters that
    // minimise sum_E ||sigma^ - sigma_c||^2. They are the null vectors of
    // the node systems (one per interior or Dirichlet vertex and
    // component) and the edge bubbles (one per edge with unknown tractions
    // and component). On each owned cell, sigma^ = sigma^_0 + sum_j alpha_j
    // S_j with S_j the response of the local problem to the change of the
    // edge tractions per unit of parameter j; the minimum solves
    // H alpha = -g with
    //   H_ij = sum_E (S_i, S_j)_E,  g_i = sum_E (S_i, sigma^_0 - sigma_c)_E,
    // assembled like a stiffness matrix: the parameters are named by the
    // vertex and edge DoFs of the continuous quadratic element on the same
    // mesh, which also gives the matrix's pattern and its
    // parallel layout. The moments and bubbles are updated in place.
    void
    optimise_free_parameters(const ElasticBody                   &body,
                             const std::vector<CellData>         &cells,
                             std::vector<FaceData>               &faces,
                             const LocalNeumannProblem           &local,
                             const TrilinosWrappers::MPI::Vector &u_kinematic,
                             const CellLoad                      &cell_load,
                             const FaceWork                      &face_work,
                             const bool                           with_bubbles,
                             EquilibratedStressErrors            &result)
    {
      const auto    &tria = body.triangulation();
      const MPI_Comm comm = tria.get_communicator();
      // Quadratic elements: one DoF per vertex and one per edge, whatever
      // p (deal.II 9.4 has no cubic FE_SimplexP).
      std::unique_ptr<FiniteElement<2>> scalar;
      if (body.is_simplex_mesh())
        scalar = std::make_unique<FE_SimplexP<2>>(2);
      else
        scalar = std::make_unique<FE_Q<2>>(2);
      const FESystem<2> names_fe(*scalar, 2);
      DoFHandler<2>     names(tria);
      names.distribute_dofs(names_fe);
      const IndexSet owned = names.locally_owned_dofs();
      IndexSet       relevant;
      DoFTools::extract_locally_relevant_dofs(names, relevant);
      DynamicSparsityPattern dsp(relevant);
      DoFTools::make_sparsity_pattern(names, dsp);
      SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
      TrilinosWrappers::SparseMatrix H;
      H.reinit(owned, owned, dsp, comm);
      TrilinosWrappers::MPI::Vector g(owned, comm), alpha(owned, comm);

      // Each cell's estimate is a quadratic in its parameters alpha_E,
      //   ||sigma^ - sigma_c||^2_E = c + 2 g . alpha_E + alpha_E . H alpha_E,
      // and ||sigma^ + sigma_c||^2_E exceeds it by 4 (sigma^, sigma_c)_E =
      // 4 (t0 + t . alpha_E). Keeping c, g, H, t0, t per cell (about 1 KB
      // for a P1 triangle, while the estimate runs) gives the errors once
      // alpha is known, without a second pass of local problems.
      std::vector<CellForm>                forms;
      std::vector<types::global_dof_index> form_names;
      std::vector<double>                  form_data;
      double                               before = 0;

      // Every face starts without named parameters; the cells name them
      // (both cells of a face give the same names).
      for (auto &face : faces)
        face.parameter_of_node.assign(face.nodes.size(),
                                      {{numbers::invalid_dof_index,
                                        numbers::invalid_dof_index}});

      // The cells are independent until their contributions are added:
      // WorkStream runs cell_form() on the threads deal.II may use and
      // add_cell_form() in the cells' order, so the sums and the result
      // do not depend on the number of threads.
      std::vector<unsigned int> owned_slots;
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        if (cells[slot].owned)
          owned_slots.push_back(slot);

      const auto cell_form = [&](const std::vector<unsigned int>::const_iterator
                                   &slot_iterator,
                                 CellScratch &scratch,
                                 CellCopy    &copy) {
        const unsigned int         slot  = *slot_iterator;
        const auto                &cell  = cells[slot].cell;
        LocalNeumannProblem       &local = scratch.local;
        Vector<double>            &load  = scratch.load;
        const unsigned int         M     = local.n_coefficients() / 2;
        auto                      &name_dofs = scratch.name_dofs;
        local.reinit(cell, u_kinematic);
        cell_load(local, slot, load);
        copy.defect = local.load_defect(load);
        // The solution's stress ignores the load's rigid-motion part
        // (round-off, or the body force's quadrature); its whitened length
        // would not.
        local.remove_rigid_load(load);

        const DoFHandler<2>::active_cell_iterator name_cell(&tria,
                                                            cell->level(),
                                                            cell->index(),
                                                            &names);
        name_cell->get_dof_indices(name_dofs);
        const auto name = [&](const unsigned int c, const unsigned int k) {
          return name_dofs[names_fe.component_to_system_index(c, k)];
        };
        // The loads of the cell's free parameters, from the work W of each
        // face's traction basis (the nodal polynomials, then the bubble)
        // on the monomials.
        unsigned int n_directions = 0;
        const auto   direction =
          [&](const types::global_dof_index dof) -> Vector<double> & {
          for (unsigned int i = 0; i < n_directions; ++i)
            if (scratch.direction_dofs[i] == dof)
              return scratch.direction_loads[i];
          if (n_directions == scratch.direction_loads.size())
            {
              scratch.direction_loads.emplace_back(local.n_coefficients());
              scratch.direction_dofs.push_back(dof);
            }
          scratch.direction_dofs[n_directions]  = dof;
          scratch.direction_loads[n_directions] = 0;
          return scratch.direction_loads[n_directions++];
        };
        copy.node_names.clear();
        copy.node_name_dofs.clear();
        copy.bubble_names.clear();
        copy.bubble_name_dofs.clear();
        for (const unsigned int f : cell->face_indices())
          {
            const unsigned int face_index = cells[slot].faces[f];
            const FaceData    &face       = faces[face_index];
            const unsigned int n_face     = face.nodes.size();
            face_work(local, slot, face, scratch.W);
            for (unsigned int c = 0; c < 2; ++c)
              {
                // A vertex's null vector changes F on the faces through it
                // (moments b[k] += kernel[k]).
                for (unsigned int k = 0; k < n_face; ++k)
                  if (face.kernel[k][c] != 0)
                    {
                      unsigned int v = 0;
                      while (v < cell->n_vertices() &&
                             cells[slot].component_dofs[v][c] !=
                               face.node_dofs[k][c])
                        ++v;
                      Assert(v < cell->n_vertices(), ExcInternalError());
                      copy.node_names.push_back({{face_index, k, c}});
                      copy.node_name_dofs.push_back(name(c, v));
                      Vector<double> &d = direction(name(c, v));
                      for (unsigned int l = 0; l < n_face; ++l)
                        {
                          const double coefficient =
                            face.mass_inverse(l, k) * face.kernel[k][c];
                          for (unsigned int m = 0; m < M; ++m)
                            d(c * M + m) += coefficient * scratch.W(m, l);
                        }
                    }
                // The edge bubble, named by the edge's DoF.
                if (with_bubbles && face.unknown[c])
                  {
                    const types::global_dof_index dof =
                      name(c, cell->n_vertices() + f);
                    copy.bubble_names.push_back({{face_index, c}});
                    copy.bubble_name_dofs.push_back(dof);
                    Vector<double> &d = direction(dof);
                    for (unsigned int m = 0; m < M; ++m)
                      d(c * M + m) += scratch.W(m, n_face);
                  }
              }
          }
        copy.names.assign(scratch.direction_dofs.begin(),
                          scratch.direction_dofs.begin() + n_directions);

        // With K = L L^T and w = L^-1 l, the energy product of two
        // responses is (S_i, S_j) = w_i . w_j, and the one of S_i with
        // sigma^_0 - sigma_c is w_i . (w_0 - w_c), w_c = L^-1 (sigma_c's
        // work). The part of sigma_c outside the local stress space adds
        // ||sigma_c||^2 - |w_c|^2 (0 up to round-off where sigma_c is a
        // polynomial of the space, as on triangles).
        const Vector<double> &w_c           = local.whitened_kinematic_work();
        Vector<double>       &base_whitened = scratch.base_whitened;
        local.whiten(load, base_whitened);
        copy.form.active_cell_index = cell->active_cell_index();
        copy.form.n                 = n_directions;
        copy.form.t0                = base_whitened * w_c;
        base_whitened -= w_c;
        copy.form.c = base_whitened.norm_sqr() +
                      std::max(local.kinematic_energy() - w_c.norm_sqr(), 0.);
        const unsigned int n = n_directions;
        scratch.whitened.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          local.whiten(scratch.direction_loads[i], scratch.whitened[i]);
        copy.H.reinit(n, n);
        copy.g.resize(n);
        copy.packed.clear();
        for (unsigned int i = 0; i < n; ++i)
          {
            for (unsigned int j = 0; j <= i; ++j)
              {
                copy.H(i, j) = copy.H(j, i) =
                  scratch.whitened[i] * scratch.whitened[j];
                copy.packed.push_back(copy.H(i, j));
              }
            copy.g[i] = scratch.whitened[i] * base_whitened;
          }
        copy.packed.insert(copy.packed.end(), copy.g.begin(), copy.g.end());
        for (unsigned int i = 0; i < n; ++i)
          copy.packed.push_back(scratch.whitened[i] * w_c);
      };

      const auto add_cell_form = [&](const CellCopy &copy) {
        result.local_problem_defect =
          std::max(result.local_problem_defect, copy.defect);
        CellForm form     = copy.form;
        form.names_offset = form_names.size();
        form.data_offset  = form_data.size();
        before += form.c;
        forms.push_back(form);
        form_names.insert(form_names.end(), copy.names.begin(), copy.names.end());
        form_data.insert(form_data.end(), copy.packed.begin(), copy.packed.end());
        for (unsigned int i = 0; i < copy.node_names.size(); ++i)
          {
            const auto [face, k, c] = copy.node_names[i];
            faces[face].parameter_of_node[k][c] = copy.node_name_dofs[i];
          }
        for (unsigned int i = 0; i < copy.bubble_names.size(); ++i)
          {
            const auto [face, c] = copy.bubble_names[i];
            faces[face].parameter_of_bubble[c] = copy.bubble_name_dofs[i];
          }
        if (copy.names.size() > 0)
          {
            H.add(copy.names, copy.H);
            g.add(copy.names, copy.g);
          }
      };

      WorkStream::run(owned_slots.cbegin(),
                      owned_slots.cend(),
                      cell_form,
                      add_cell_form,
                      CellScratch(local, names_fe.n_dofs_per_cell()),
                      CellCopy());
      H.compress(VectorOperation::add);
      g.compress(VectorOperation::add);
      result.error_squared_before_optimisation =
        Utilities::MPI::sum(before, comm);

      // Names without a free parameter (vertices on loaded edges, edges
      // with known tractions, the interior DoF of Q2) get alpha = 0.
      for (const auto i : owned)
        if (H.diag_element(i) == 0)
          H.set(i, i, 1.);
      H.compress(VectorOperation::insert);
      g *= -1;
      const double g_norm = g.l2_norm();
      // The estimate is the quadratic's value, whose excess over the
      // minimum is r^T H^-1 r for the residual r: quadratic in the
      // residual. 1e-6 leaves the estimates of the test suite unchanged
      // in their printed digits with about 70 % of the steps 1e-8 took;
      // 1e-4 changed the seed example's adapted mesh (928 -> 924 cells).
      if (g_norm > 0)
        {
          SolverControl control(1000, 1e-6 * g_norm);
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          TrilinosWrappers::PreconditionJacobi    jacobi;
          jacobi.initialize(H);
          try
            {
              cg.solve(H, alpha, g, jacobi);
            }
          catch (const SolverControl::NoConvergence &)
            {
              // The last iterate is as admissible as the solution.
            }
          result.optimisation_iterations = control.last_step();
        }

      TrilinosWrappers::MPI::Vector alpha_local(owned, relevant, comm);
      alpha_local = alpha;
      for (auto &face : faces)
        for (unsigned int c = 0; c < 2; ++c)
          {
            for (unsigned int k = 0; k < face.parameter_of_node.size(); ++k)
              if (face.parameter_of_node[k][c] != numbers::invalid_dof_index)
                face.moments[k][c] +=
                  alpha_local(face.parameter_of_node[k][c]) * face.kernel[k][c];
            if (face.parameter_of_bubble[c] != numbers::invalid_dof_index)
              face.bubble[c] = alpha_local(face.parameter_of_bubble[c]);
          }

      // The errors from each cell's quadratic at the optimal alpha. The
      // expansion cancels at most what the optimisation gained over the
      // classical estimate, far from round-off.
      result.error_squared.reinit(tria.n_active_cells());
      double         sum_norm = 0;
      Vector<double> alpha_cell;
      for (const CellForm &form : forms)
        {
          const unsigned int n = form.n;
          alpha_cell.reinit(n, true);
          for (unsigned int i = 0; i < n; ++i)
            alpha_cell(i) = alpha_local(form_names[form.names_offset + i]);
          const double *packed = &form_data[form.data_offset];
          const double *g_cell = packed + n * (n + 1) / 2;
          const double *t_cell = g_cell + n;
          double        error = form.c, product = form.t0;
          for (unsigned int i = 0; i < n; ++i)
            {
              double H_alpha = 0;
              for (unsigned int j = 0; j < n; ++j)
                H_alpha += packed[i >= j ? i * (i + 1) / 2 + j :
                                           j * (j + 1) / 2 + i] *
                           alpha_cell(j);
              error += alpha_cell(i) * (2 * g_cell[i] + H_alpha);
              product += alpha_cell(i) * t_cell[i];
            }
          error = std::max(error, 0.);
          result.error_squared(form.active_cell_index) = error;
          sum_norm += error + 4 * product;
        }
      result.sum_norm_squared = Utilities::MPI::sum(sum_norm, comm);
    }
  } // namespace equilibration
} // namespace coulomb_adapt
