#include <deal.II/base/array_view.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <coulomb_adapt/core/optional_timer_section.h>
#include <coulomb_adapt/indicator/equilibration_mesh.h>
#include <coulomb_adapt/indicator/local_problem_loads.h>
#include <coulomb_adapt/indicator/traction_optimisation.h>
#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>
#include <coulomb_adapt/solvers/symmetric_direct_solver.h>
#include <coulomb_adapt/solvers/truncated_minimisation.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <map>
#include <memory>
#include <optional>

namespace coulomb_adapt
{
  namespace equilibration
  {
    namespace
    {
      // The names of the free parameters: the vertex and edge DoFs of the
      // continuous quadratic element on the same mesh (one DoF per vertex
      // and one per edge whatever p; deal.II 9.4 has no cubic
      // FE_SimplexP; components 0 and 1 for the node systems' null vectors
      // and the bubbles, with the relaxed modes a third for the couple
      // modes (vertices) and the linear tangential ones (edges), and for
      // p >= 2 a fourth and a fifth for the edges' quadratic tangential
      // and normal modes), which also give the pattern of the parameters'
      // system and its parallel layout.
      struct ParameterNames
      {
        ParameterNames(const ElasticBody &body, const bool relaxed)
          : scalar(body.is_simplex_mesh() ?
                     std::unique_ptr<FiniteElement<2>>(new FE_SimplexP<2>(2)) :
                     std::unique_ptr<FiniteElement<2>>(new FE_Q<2>(2)))
          , quadratic_modes(relaxed && body.dof_handler().get_fe().degree >= 2)
          , fe(*scalar,
               !relaxed        ? 2 :
               quadratic_modes ? 5 :
                                 3)
          , dof_handler(body.triangulation())
        {
          dof_handler.distribute_dofs(fe);
          owned = dof_handler.locally_owned_dofs();
          DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
        }

        std::unique_ptr<FiniteElement<2>> scalar;
        // Whether the edges carry the quadratic modes (add_relaxed_modes()).
        bool          quadratic_modes;
        FESystem<2>   fe;
        DoFHandler<2> dof_handler;
        IndexSet      owned, relevant;
      };

      // Where a cell's quadratic form sits in CellForms' flat arrays.
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
        Vector<double>                       load;
        std::vector<types::global_dof_index> name_dofs, direction_dofs;
        std::vector<Vector<double>>          direction_loads;
        FullMatrix<double>                   W;
        // quadratic_form(): the loads as columns of a row-major matrix,
        // whitened in place, and the lower triangle of their Gram matrix.
        std::vector<double> columns, gram;
        // cell_error_at(): a whitened load.
        Vector<double> w;
      };

      // What a cell adds: its quadratic form (packed = H's lower triangle
      // by rows, g, t) and the names of its parameters.
      struct CellCopy
      {
        CellForm                             form;
        double                               defect = 0;
        std::vector<types::global_dof_index> names;
        std::vector<double>                  packed;
      };

      // What every cell reads.
      struct FormInputs
      {
        const std::vector<CellData>         &cells;
        const std::vector<FaceData>         &faces;
        const LocalProblemLoads             &loads;
        const TrilinosWrappers::MPI::Vector &u_kinematic;
        const ParameterNames                &names;
        const bool                           with_bubbles;
        // The relaxed modes (see add_relaxed_modes()); empty when they are
        // not used. Per vertex (named by its x DoF): every face through it
        // has unknown tractions, so its star can carry a couple mode.
        const std::map<types::global_dof_index, bool> *couple_allowed;
      };



      // The relaxed modes: edge tractions that keep every cell in
      // equilibrium without the prolongation conditions, so sigma^ stays
      // admissible while the minimisation sees more of the admissible set.
      // Of the self-equilibrated tractions on one edge (zero force and
      // couple), the linear Legendre polynomial along the edge's tangent,
      // named by the edge's third-component DoF. And per vertex whose star
      // has unknown tractions everywhere, a linear normal traction on each
      // edge through it with couple +1 on the cell counterclockwise of the
      // edge (seen from the vertex) and -1 on the other one: each cell gets
      // +1 and -1 from its two edges there, named by the vertex's
      // third-component DoF. W's column n + 1 (n the face's nodes) is the
      // linear Legendre polynomial's work (with the cell's orientation
      // eta).
      // For p >= 2 the quadratic Legendre polynomial P2 is also
      // self-equilibrated along the edge in both directions (zero force;
      // zero couple, since it is orthogonal to 1 and s), and it lies in
      // the span of the face's nodal polynomials, whose moments the node
      // systems fix: so P2 tangent and P2 normal are two more modes per
      // edge, named by the edge's fourth- and fifth-component DoFs (W's
      // column n + 2). For p = 1, P2 is the edge bubble (degree p + 1),
      // already a parameter.
      template <typename Name, typename Direction>
      void
      add_relaxed_modes(const FormInputs         &in,
                        const unsigned int        slot,
                        const unsigned int        f,
                        const FullMatrix<double> &W,
                        const Name               &name,
                        const Direction          &direction)
      {
        const CellData &data = in.cells[slot];
        const auto     &cell = data.cell;
        const FaceData &face = in.faces[data.faces[f]];
        // W's columns of the linear and the quadratic Legendre polynomial.
        const unsigned int linear_column    = face.nodes.size() + 1;
        const unsigned int quadratic_column = face.nodes.size() + 2;
        const unsigned int M                = W.m();
        const Tensor<1, 2> tangent          = (face.v1 - face.v0) / face.length;
        const double       eta = face.plus == static_cast<int>(slot) ? 1 : -1;
        // A traction along @p direction may move where each component it
        // has is unknown (on a sliding support: the normal one only).
        const auto may_move = [&](const Tensor<1, 2> &direction_vector) {
          for (unsigned int c = 0; c < 2; ++c)
            if (!face.unknown[c] && std::abs(direction_vector[c]) >= 1e-12)
              return false;
          return true;
        };
        const auto add_mode = [&](const unsigned int  component,
                                  const Tensor<1, 2> &direction_vector,
                                  const unsigned int  w_column) {
          Vector<double> &d =
            direction(name(component, cell->n_vertices() + f));
          for (unsigned int c = 0; c < 2; ++c)
            for (unsigned int m = 0; m < M; ++m)
              d(c * M + m) += direction_vector[c] * W(m, w_column);
        };
        if (may_move(tangent))
          add_mode(2, tangent, linear_column);
        if (in.names.quadratic_modes)
          {
            if (may_move(tangent))
              add_mode(3, tangent, quadratic_column);
            if (may_move(face.normal))
              add_mode(4, face.normal, quadratic_column);
          }
        if (!(face.unknown[0] && face.unknown[1]))
          return;
        Point<2> centroid;
        for (unsigned int v = 0; v < cell->n_vertices(); ++v)
          centroid += data.points[v] / cell->n_vertices();
        // The couple of the traction P1(s) n_out on this cell is
        // L^2/6 (tangent x n_out), n_out = eta normal.
        const double raw =
          eta * (tangent[0] * face.normal[1] - tangent[1] * face.normal[0]);
        for (unsigned int v = 0; v < cell->n_vertices(); ++v)
          {
            const Point<2> &x     = data.points[v];
            const bool      at_v0 = x.distance(face.v0) < 1e-12 * face.length;
            const bool      at_v1 = x.distance(face.v1) < 1e-12 * face.length;
            if (!(at_v0 || at_v1))
              continue;
            const auto a = in.couple_allowed->find(data.nodes[v]);
            if (a == in.couple_allowed->end() || !a->second)
              continue;
            const Tensor<1, 2> along       = (at_v0 ? face.v1 : face.v0) - x;
            const Tensor<1, 2> to_centroid = centroid - x;
            const double       desired =
              along[0] * to_centroid[1] - along[1] * to_centroid[0] > 0 ? 1 :
                                                                                -1;
            const double scale =
              desired / raw * 6 / (face.length * face.length);
            Vector<double> &d = direction(name(2, v));
            for (unsigned int c = 0; c < 2; ++c)
              for (unsigned int m = 0; m < M; ++m)
                d(c * M + m) += scale * face.normal[c] * W(m, linear_column);
          }
      }



      // The loads of the cell's free parameters (its "directions"), from
      // the work W of each face's traction basis (the nodal polynomials,
      // the bubble, the linear and quadratic Legendre polynomials:
      // LocalProblemLoads::face_work()) on the monomials; the parameters'
      // names go to copy. Returns their number.
      unsigned int
      parameter_loads(const FormInputs  &in,
                      const unsigned int slot,
                      CellScratch       &scratch,
                      CellCopy          &copy)
      {
        const auto                &cell  = in.cells[slot].cell;
        const LocalNeumannProblem &local = scratch.local;
        const unsigned int         M     = local.n_coefficients() / 2;
        const DoFHandler<2>::active_cell_iterator name_cell(
          &cell->get_triangulation(),
          cell->level(),
          cell->index(),
          &in.names.dof_handler);
        name_cell->get_dof_indices(scratch.name_dofs);
        const auto name = [&](const unsigned int c, const unsigned int k) {
          return scratch.name_dofs[in.names.fe.component_to_system_index(c, k)];
        };
        unsigned int n = 0;
        const auto   direction =
          [&](const types::global_dof_index dof) -> Vector<double> & {
          for (unsigned int i = 0; i < n; ++i)
            if (scratch.direction_dofs[i] == dof)
              return scratch.direction_loads[i];
          if (n == scratch.direction_loads.size())
            {
              scratch.direction_loads.emplace_back(local.n_coefficients());
              scratch.direction_dofs.push_back(dof);
            }
          scratch.direction_dofs[n]  = dof;
          scratch.direction_loads[n] = 0;
          return scratch.direction_loads[n++];
        };
        for (const unsigned int f : cell->face_indices())
          {
            const unsigned int face_index = in.cells[slot].faces[f];
            const FaceData    &face       = in.faces[face_index];
            const unsigned int n_face     = face.nodes.size();
            in.loads.face_work(local, slot, face, scratch.W);
            for (unsigned int c = 0; c < 2; ++c)
              {
                // A vertex's null vector changes F on the faces through it
                // (moments b[k] += kernel[k]).
                for (unsigned int k = 0; k < n_face; ++k)
                  if (face.kernel[k][c] != 0)
                    {
                      unsigned int v = 0;
                      while (v < cell->n_vertices() &&
                             in.cells[slot].component_dofs[v][c] !=
                               face.node_dofs[k][c])
                        ++v;
                      Assert(v < cell->n_vertices(), ExcInternalError());
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
                if (in.with_bubbles && face.unknown[c])
                  {
                    const types::global_dof_index dof =
                      name(c, cell->n_vertices() + f);
                    Vector<double> &d = direction(dof);
                    for (unsigned int m = 0; m < M; ++m)
                      d(c * M + m) += scratch.W(m, n_face);
                  }
              }
            if (in.couple_allowed != nullptr)
              add_relaxed_modes(in, slot, f, scratch.W, name, direction);
          }
        copy.names.assign(scratch.direction_dofs.begin(),
                          scratch.direction_dofs.begin() + n);
        return n;
      }



      // The cell's quadratic form. With K = L L^T and w = L^-1 l, the
      // energy product of two responses is (S_i, S_j) = w_i . w_j, and
      // the one of S_i with sigma^_0 - sigma_c is w_i . (w_0 - w_c),
      // w_c = L^-1 (sigma_c's work). The part of sigma_c outside the
      // local stress space adds ||sigma_c||^2 - |w_c|^2 (0 up to
      // round-off where sigma_c is a polynomial of the space, as on
      // triangles). All loads are whitened by one forward substitution,
      // and every product is an entry of the Gram matrix of the columns
      // w_1 ... w_n, w_0 - w_c, w_c, summed row by row of the whitened
      // loads (independent multiply-adds, no chain of dot products).
      void
      quadratic_form(const unsigned int n, CellScratch &scratch, CellCopy &copy)
      {
        const LocalNeumannProblem &local = scratch.local;
        const Vector<double>      &w_c   = local.whitened_kinematic_work();
        // With a lift of the displacement data, sigma_c is the lifted
        // stress and the normalisation (with the FE stress) has products
        // of its own, in a column of their own.
        const bool            lifted = local.has_kinematic_lift();
        const Vector<double> &w_fe   = local.whitened_normalisation_work();
        const unsigned int    N      = local.n_coefficients();
        const unsigned int    stride = n + 2 + (lifted ? 1 : 0);
        std::vector<double>  &X      = scratch.columns;
        X.resize(N * stride);
        for (unsigned int a = 0; a < N; ++a)
          {
            for (unsigned int i = 0; i < n; ++i)
              X[a * stride + i] = scratch.direction_loads[i](a);
            X[a * stride + n] = scratch.load(a);
          }
        local.whiten_many(X.data(), n + 1, stride);
        double t0 = local.normalisation_offset();
        for (unsigned int a = 0; a < N; ++a)
          {
            double *const x = &X[a * stride];
            t0 += x[n] * w_fe(a);
            x[n] -= w_c(a);
            x[n + 1] = w_c(a);
            if (lifted)
              x[n + 2] = w_fe(a);
          }
        std::vector<double> &G = scratch.gram;
        G.resize(stride * stride);
        LocalNeumannProblem::gram_lower(X.data(), stride, N, G.data());
        copy.form.n  = n;
        copy.form.t0 = t0;
        copy.form.c =
          G[n * stride + n] +
          std::max(local.kinematic_energy() - G[(n + 1) * stride + n + 1], 0.);
        // packed = H's lower triangle by rows, g, t.
        copy.packed.resize(n * (n + 1) / 2 + 2 * n);
        double *packed = copy.packed.data();
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j <= i; ++j)
            *packed++ = G[i * stride + j];
        for (unsigned int i = 0; i < n; ++i)
          *packed++ = G[n * stride + i];
        const unsigned int product_row = lifted ? n + 2 : n + 1;
        for (unsigned int i = 0; i < n; ++i)
          *packed++ = G[product_row * stride + i];
      }



      // Adds a cell's H to the parameters' matrix, whose pattern is fixed:
      // locally owned rows are summed straight into the matrix's row by
      // local indices, the cell's columns (looked up once and sorted) found
      // by one pass along the sorted row, instead of Epetra's
      // SumIntoGlobalValues with a global-to-local lookup and a binary
      // search per entry (about a fifth of the cells' forms). Rows owned by
      // another rank (a ghost cell's names) go through deal.II as before.
      // The same sums in the same order: the matrix is the same to the bit.
      void
      add_cell_matrix(const std::vector<types::global_dof_index> &names,
                      const FullMatrix<double>                   &cell_H,
                      TrilinosWrappers::SparseMatrix             &H,
                      std::vector<std::pair<int, unsigned int>>  &columns)
      {
        const Epetra_CrsMatrix &matrix = H.trilinos_matrix();
        const unsigned int      n      = names.size();
        columns.resize(n);
        for (unsigned int j = 0; j < n; ++j)
          columns[j] = {matrix.LCID(static_cast<int>(names[j])), j};
        std::sort(columns.begin(), columns.end());
        for (unsigned int i = 0; i < n; ++i)
          {
            const int row     = matrix.LRID(static_cast<int>(names[i]));
            int       length  = 0;
            double   *values  = nullptr;
            int      *indices = nullptr;
            if (row < 0 ||
                matrix.ExtractMyRowView(row, length, values, indices) != 0)
              {
                H.add(names[i], n, names.data(), &cell_H(i, 0));
                continue;
              }
            int position = 0;
            for (const auto &[column, j] : columns)
              {
                while (position < length && indices[position] < column)
                  ++position;
                AssertThrow(position < length && indices[position] == column,
                            ExcInternalError());
                values[position] += cell_H(i, j);
              }
          }
      }



      // The local problem of cell @p slot factored and the load of
      // sigma^_0 in scratch.load, its rigid-motion part (its defect) in
      // copy.defect and removed: the solution's stress ignores it
      // (round-off, or the body force's quadrature); its whitened length
      // would not.
      void
      prepare_cell(const FormInputs  &in,
                   const unsigned int slot,
                   CellScratch       &scratch,
                   CellCopy          &copy)
      {
        scratch.local.reinit(in.cells[slot].cell, in.u_kinematic);
        in.loads.cell_load(scratch.local, slot, scratch.load);
        copy.defect = scratch.local.load_defect(scratch.load);
        scratch.local.remove_rigid_load(scratch.load);
      }



      // Everything of one owned cell (run on any thread).
      void
      cell_form(const FormInputs  &in,
                const unsigned int slot,
                CellScratch       &scratch,
                CellCopy          &copy)
      {
        prepare_cell(in, slot, scratch, copy);
        copy.form.active_cell_index = in.cells[slot].cell->active_cell_index();
        quadratic_form(parameter_loads(in, slot, scratch, copy), scratch, copy);
      }



      // The quadratic forms of the owned cells. Each cell's estimate is a
      // quadratic in its parameters alpha_E,
      //   ||sigma^ - sigma_c||^2_E = c + 2 g . alpha_E + alpha_E . H alpha_E,
      // and ||sigma^ + sigma_c||^2_E exceeds it by 4 (sigma^, sigma_c)_E =
      // 4 (t0 + t . alpha_E). Keeping c, g, H, t0, t per cell (about 1 KB
      // for a P1 triangle, while the estimate runs) gives the errors once
      // alpha is known, without a second pass of local problems.
      class CellForms
      {
      public:
        void
        add(const CellCopy &copy)
        {
          CellForm form     = copy.form;
          form.names_offset = names.size();
          form.data_offset  = data.size();
          classical += form.c;
          forms.push_back(form);
          names.insert(names.end(), copy.names.begin(), copy.names.end());
          data.insert(data.end(), copy.packed.begin(), copy.packed.end());
        }

        // sum_E c: the estimate with alpha = 0 (the classical technique).
        double
        classical_sum() const
        {
          return classical;
        }

        // The errors at @p alpha (ghosted). The expansion cancels at most
        // what the optimisation gained over the classical estimate, far
        // from round-off.
        void
        errors(const TrilinosWrappers::MPI::Vector &alpha,
               const unsigned int                   n_active_cells,
               EquilibratedStressErrors            &result) const
        {
          result.error_squared.reinit(n_active_cells);
          double         sum_norm = 0;
          Vector<double> a;
          for (const CellForm &form : forms)
            {
              const unsigned int n = form.n;
              a.reinit(n, true);
              for (unsigned int i = 0; i < n; ++i)
                a(i) = alpha(names[form.names_offset + i]);
              const double *H     = &data[form.data_offset];
              const double *g     = H + n * (n + 1) / 2;
              const double *t     = g + n;
              double        error = form.c, product = form.t0;
              for (unsigned int i = 0; i < n; ++i)
                {
                  double H_a = 0;
                  for (unsigned int j = 0; j < n; ++j)
                    H_a +=
                      H[i >= j ? i * (i + 1) / 2 + j : j * (j + 1) / 2 + i] *
                      a(j);
                  error += a(i) * (2 * g[i] + H_a);
                  product += a(i) * t[i];
                }
              error = std::max(error, 0.);
              result.error_squared(form.active_cell_index) = error;
              sum_norm += error + 4 * product;
            }
          result.sum_norm_squared =
            Utilities::MPI::sum(sum_norm, alpha.get_mpi_communicator());
        }

        // Every cell's H and g added to the parameters' matrix @p H and
        // vector @p g, in the cells' order (the copier's order).
        void
        add_to(TrilinosWrappers::SparseMatrix &H,
               TrilinosWrappers::MPI::Vector  &g) const
        {
          std::vector<std::pair<int, unsigned int>> columns;
          std::vector<types::global_dof_index>      cell_names;
          FullMatrix<double>                        cell_H;
          for (const CellForm &form : forms)
            {
              const unsigned int n = form.n;
              if (n == 0)
                continue;
              cell_names.assign(names.begin() + form.names_offset,
                                names.begin() + form.names_offset + n);
              cell_H.reinit(n, n, true);
              const double *packed = &data[form.data_offset];
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j <= i; ++j)
                  cell_H(i, j) = cell_H(j, i) = *packed++;
              add_cell_matrix(cell_names, cell_H, H, columns);
              g.add(cell_names, std::vector<double>(packed, packed + n));
            }
        }

      private:
        std::vector<CellForm>                forms;
        std::vector<types::global_dof_index> names;
        std::vector<double>                  data;
        double                               classical = 0;
      };



      // ||sigma^ - sigma_c||^2 on the current cell of @p local for the
      // response to @p load, and (sigma^, sigma_c).
      std::array<double, 2>
      error_and_product(const LocalNeumannProblem &local,
                        const Vector<double>      &load,
                        Vector<double>            &w)
      {
        local.whiten(load, w);
        const Vector<double> &w_c   = local.whitened_kinematic_work();
        const Vector<double> &w_fe  = local.whitened_normalisation_work();
        double                error = 0, product = local.normalisation_offset(),
               w_c_squared = 0;
        for (unsigned int a = 0; a < w.size(); ++a)
          {
            error += (w(a) - w_c(a)) * (w(a) - w_c(a));
            product += w(a) * w_fe(a);
            w_c_squared += w_c(a) * w_c(a);
          }
        return {{error + std::max(local.kinematic_energy() - w_c_squared, 0.),
                 product}};
      }



      // The error of one owned cell at the parameters @p alpha (ghosted)
      // from the local problem of @p in's degree, solved once for the
      // whole load: the load of sigma^_0 plus alpha_j times that of
      // parameter j (copy.form.c: ||sigma^ - sigma_c||^2, t0: (sigma^,
      // sigma_c), as for a form with no parameters; packed: the error at
      // alpha = 0, the classical estimate, with the same local problem).
      void
      cell_error_at(const FormInputs                    &in,
                    const TrilinosWrappers::MPI::Vector &alpha,
                    const unsigned int                   slot,
                    CellScratch                         &scratch,
                    CellCopy                            &copy)
      {
        prepare_cell(in, slot, scratch, copy);
        const LocalNeumannProblem &local = scratch.local;
        Vector<double>            &w     = scratch.w;
        const auto classical = error_and_product(local, scratch.load, w);
        copy.packed.assign(classical.begin(), classical.end());
        const unsigned int n = parameter_loads(in, slot, scratch, copy);
        for (unsigned int i = 0; i < n; ++i)
          scratch.load.add(alpha(copy.names[i]), scratch.direction_loads[i]);
        const auto [error, product] = error_and_product(local, scratch.load, w);
        copy.form                   = CellForm();
        copy.form.active_cell_index = in.cells[slot].cell->active_cell_index();
        copy.form.c                 = error;
        copy.form.t0                = product;
      }



      // The errors at @p alpha from the local problems of @p in (a higher
      // degree than the minimisation's), cell by cell on the threads.
      void
      errors_at(const FormInputs                    &in,
                const LocalNeumannProblem           &local,
                const std::vector<unsigned int>     &owned_slots,
                const TrilinosWrappers::MPI::Vector &alpha,
                const unsigned int                   n_active_cells,
                EquilibratedStressErrors            &result)
      {
        result.error_squared.reinit(n_active_cells);
        Vector<double> classical_squared(n_active_cells);
        double         sum_norm = 0, classical = 0, classical_sum_norm = 0;
        WorkStream::run(
          owned_slots.cbegin(),
          owned_slots.cend(),
          [&](const std::vector<unsigned int>::const_iterator &slot,
              CellScratch                                     &scratch,
              CellCopy                                        &copy) {
            cell_error_at(in, alpha, *slot, scratch, copy);
          },
          [&](const CellCopy &copy) {
            result.local_problem_defect =
              std::max(result.local_problem_defect, copy.defect);
            result.error_squared(copy.form.active_cell_index) = copy.form.c;
            sum_norm += copy.form.c + 4 * copy.form.t0;
            classical_squared(copy.form.active_cell_index) = copy.packed[0];
            classical += copy.packed[0];
            classical_sum_norm += copy.packed[0] + 4 * copy.packed[1];
          },
          CellScratch(local, in.names.fe.n_dofs_per_cell()),
          CellCopy());
        // Every rank takes part in every sum, whatever the comparison.
        const MPI_Comm            comm = alpha.get_mpi_communicator();
        const std::vector<double> own  = {sum_norm,
                                          classical,
                                          classical_sum_norm,
                                          result.error_squared.l1_norm()};
        std::vector<double>       totals(own.size());
        Utilities::MPI::sum(make_array_view(own),
                            comm,
                            make_array_view(totals));
        result.sum_norm_squared                  = totals[0];
        result.error_squared_before_optimisation = totals[1];
        // Both sigma^ are statically admissible and evaluated with the
        // same local problems: where the minimum of the minimisation's
        // local problems is above the classical tractions' estimate here
        // (Q2 with k = 3 on the manufactured solution, both bodies
        // optimised: effectivity 1.15 against the classical tractions'
        // 1.11), the body keeps the classical ones.
        if (totals[1] < totals[3])
          {
            result.error_squared               = classical_squared;
            result.sum_norm_squared            = totals[2];
            result.optimisation_kept_classical = true;
          }
      }



      // The additive Schwarz patches of the relaxed system: per vertex
      // whose parameters this rank owns, its own names and those of the
      // edges through it (ghost cells complete the edges of every owned
      // vertex). Such a patch holds the vertex's couple mode and the
      // tangential modes and bubbles of its edges (for p >= 2 also their
      // quadratic modes: ~33 names instead of ~21), the fourth-order
      // coupling that point Jacobi misses. The stars' cells' names too
      // (patches of ~46 instead of ~20 on P1 triangles) took fewer steps
      // but about twice the flops (steps measured on the relaxed system of
      // blocks with 3 refinements, 130,275 parameters; flops counted from
      // the patch sizes; doc/indicator.md).
      std::vector<std::vector<types::global_dof_index>>
      vertex_patches(const ParameterNames &names)
      {
        const unsigned int per_vertex = names.fe.n_dofs_per_vertex();
        const unsigned int per_line   = names.fe.n_dofs_per_line();
        std::map<types::global_dof_index, std::vector<types::global_dof_index>>
          patches_of;
        for (const auto &cell : names.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() || cell->is_ghost())
            for (const unsigned int v : cell->vertex_indices())
              {
                const auto vertex = cell->vertex_dof_index(v, 0);
                if (!names.owned.is_element(vertex))
                  continue;
                auto &patch = patches_of[vertex];
                for (unsigned int k = 0; k < per_vertex; ++k)
                  patch.push_back(cell->vertex_dof_index(v, k));
                for (const unsigned int l : cell->line_indices())
                  if (cell->line(l)->vertex_index(0) == cell->vertex_index(v) ||
                      cell->line(l)->vertex_index(1) == cell->vertex_index(v))
                    for (unsigned int k = 0; k < per_line; ++k)
                      patch.push_back(cell->line(l)->dof_index(k));
              }
        std::vector<std::vector<types::global_dof_index>> patches;
        patches.reserve(patches_of.size());
        for (auto &[vertex, patch] : patches_of)
          {
            std::sort(patch.begin(), patch.end());
            patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
            patches.push_back(std::move(patch));
          }
        return patches;
      }



      // How minimise() solves H alpha = -g.
      enum class Minimisation
      {
        /** CG with Jacobi to 1e-6 (the prolongation conditions kept). */
        jacobi_cg,
        /** MUMPS's LDL^T (the relaxed modes, tolerance 0). */
        exact,
        /** CG with additive Schwarz, truncated by the estimate's decrease
         * (the relaxed modes, tolerance > 0). */
        truncated_cg
      };

      Minimisation
      minimisation_method(const bool relaxed, const double tolerance)
      {
        return !relaxed       ? Minimisation::jacobi_cg :
               tolerance == 0 ? Minimisation::exact :
                                Minimisation::truncated_cg;
      }



      // The free parameters: the names whose diagonal in H is not zero
      // (every rank).
      types::global_dof_index
      count_free_parameters(const TrilinosWrappers::SparseMatrix &H,
                            const MPI_Comm                        comm)
      {
        types::global_dof_index n = 0;
        for (const auto i : H.locally_owned_range_indices())
          n += (H.diag_element(i) != 0);
        return Utilities::MPI::sum(n, comm);
      }



      // H alpha = -g. Without the relaxed modes (jacobi_cg) by CG with
      // Jacobi: the estimate is the quadratic's value, whose excess over
      // the minimum is r^T H^-1 r for the residual r; 1e-6 leaves the
      // estimates of the test suite unchanged in their printed digits with
      // about 70 % of the steps 1e-8 took (1e-4 changed the seed example's
      // adapted mesh).
      // With the relaxed modes H is, like the complementary energy of an
      // Airy stress function, a fourth-order operator: CG with Jacobi took
      // 500 steps on the seed's 488 DoFs and did not reach 1e-6 in 1000 on
      // 26,724 (its estimate then depended on round-off, which broke its
      // homogeneity). With a tolerance > 0 (truncated_cg) it is CG
      // preconditioned by additive Schwarz over the vertices' patches, stopped
      // by the estimate's own decrease (minimise_by_truncated_cg(): relative,
      // so homogeneous; the patches follow the mesh, so the steps do not depend
      // on the
      // partition); the classical estimate @p classical is the quadratic's
      // value at alpha = 0. With tolerance 0 (exact) it is MUMPS's LDL^T of the
      // lower triangle, exact to round-off and several times slower, and
      // its memory grows faster than the mesh: above @p minimisation's
      // exact_up_to parameters the truncated CG takes over. Returns the
      // number of parameters; @p steps: the truncated CG's;
      // @p too_large: whether the exact minimisation was replaced.
      types::global_dof_index
      minimise(TrilinosWrappers::SparseMatrix &H,
               TrilinosWrappers::MPI::Vector  &g,
               TrilinosWrappers::MPI::Vector  &alpha,
               const ParameterNames           &names,
               Minimisation                    method,
               const CreMinimisation          &minimisation,
               const double                    classical,
               unsigned int                   &steps,
               bool                           &too_large)
      {
        const types::global_dof_index n_parameters =
          count_free_parameters(H, alpha.get_mpi_communicator());
        double tolerance = minimisation.tolerance;
        too_large        = method == Minimisation::exact &&
                    minimisation.exact_up_to > 0 &&
                    n_parameters > minimisation.exact_up_to;
        if (too_large)
          {
            method    = Minimisation::truncated_cg;
            tolerance = CreMinimisation::large_system_tolerance;
          }
        // The patches drop the names without a free parameter by their
        // zero diagonal, so the preconditioner comes first.
        std::unique_ptr<AdditiveSchwarzPreconditioner> schwarz;
        if (method == Minimisation::truncated_cg)
          schwarz = std::make_unique<AdditiveSchwarzPreconditioner>(
            H, vertex_patches(names), names.relevant);
        // Names without a free parameter (vertices on loaded edges, edges
        // with known tractions, the interior DoF of Q2, the vertices'
        // third component without the couple mode) get alpha = 0.
        for (const auto i : H.locally_owned_range_indices())
          if (H.diag_element(i) == 0)
            H.set(i, i, 1.);
        H.compress(VectorOperation::insert);
        g *= -1;
        const double g_norm = g.l2_norm();
        if (g_norm == 0)
          return n_parameters;
        if (method == Minimisation::truncated_cg)
          {
            steps = minimise_by_truncated_cg(
                      H, alpha, g, *schwarz, classical, tolerance, 10, 2000)
                      .steps;
            return n_parameters;
          }
        if (method == Minimisation::exact)
          {
            solve_symmetric_positive_definite(H, alpha, g);
            return n_parameters;
          }
        SolverControl                           control(1000, 1e-6 * g_norm);
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
        return n_parameters;
      }



      // FormInputs::couple_allowed: per vertex of the faces (named by its
      // x DoF), whether every face through it has unknown tractions in
      // both components.
      std::map<types::global_dof_index, bool>
      vertices_with_couple_mode(const std::vector<FaceData> &faces)
      {
        std::map<types::global_dof_index, bool> couple_allowed;
        for (const FaceData &face : faces)
          for (unsigned int k = 0; k < face.nodes.size(); ++k)
            if (is_face_end(face, k))
              {
                auto [entry, inserted] =
                  couple_allowed.emplace(face.nodes[k], true);
                entry->second =
                  entry->second && face.unknown[0] && face.unknown[1];
              }
        return couple_allowed;
      }
    } // namespace



    // Step 5 of equilibrated_stress_errors(): the free parameters that
    // minimise sum_E ||sigma^ - sigma_c||^2. They are the null vectors of
    // the node systems (one per interior or Dirichlet vertex and
    // component), the edge bubbles (one per edge with unknown tractions
    // and component) and, when @p relaxed, the modes of add_relaxed_modes().
    // On each owned cell, sigma^ = sigma^_0 + sum_j alpha_j
    // S_j with S_j the response of the local problem to the change of the
    // edge tractions per unit of parameter j; the minimum solves
    // H alpha = -g with
    //   H_ij = sum_E (S_i, S_j)_E,  g_i = sum_E (S_i, sigma^_0 - sigma_c)_E,
    // assembled like a stiffness matrix. The errors come from each cell's
    // quadratic at the minimum.
    void
    optimise_free_parameters(const ElasticBody                   &body,
                             const std::vector<CellData>         &cells,
                             const std::vector<FaceData>         &faces,
                             const LocalNeumannProblem           &local,
                             const TrilinosWrappers::MPI::Vector &u_kinematic,
                             const LocalProblemLoads             &loads,
                             const bool                           with_bubbles,
                             const bool                           relaxed,
                             const CreMinimisation               &minimisation,
                             EquilibratedStressErrors            &result,
                             const LocalProblems                 *evaluation,
                             TimerOutput                         *timer)
    {
      const MPI_Comm       comm = body.triangulation().get_communicator();
      const ParameterNames names(body, relaxed);
      std::map<types::global_dof_index, bool> couple_allowed;
      if (relaxed)
        couple_allowed = vertices_with_couple_mode(faces);
      // The cells are independent until their contributions are added:
      // WorkStream runs cell_form() on the threads deal.II may use and
      // the copier in the cells' order, so the sums and the result do not
      // depend on the number of threads. It runs as a task while this
      // thread (the one that makes MPI calls) builds H's pattern and
      // matrix, which need no form; the forms are added to H once both
      // are done, in the cells' order, the same sums as when the copier
      // added them.
      std::vector<unsigned int> owned_slots;
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        if (cells[slot].owned)
          owned_slots.push_back(slot);
      const FormInputs                    in{cells,
                          faces,
                          loads,
                          u_kinematic,
                          names,
                          with_bubbles,
                          relaxed ? &couple_allowed : nullptr};
      CellForms                           forms;
      std::optional<OptionalTimerSection> section;
      section.emplace(timer, "error indicator: cell forms");
      Threads::Task<void> forms_task = Threads::new_task([&]() {
        WorkStream::run(
          owned_slots.cbegin(),
          owned_slots.cend(),
          [&](const std::vector<unsigned int>::const_iterator &slot,
              CellScratch                                     &scratch,
              CellCopy &copy) { cell_form(in, *slot, scratch, copy); },
          [&](const CellCopy &copy) {
            result.local_problem_defect =
              std::max(result.local_problem_defect, copy.defect);
            forms.add(copy);
          },
          CellScratch(local, names.fe.n_dofs_per_cell()),
          CellCopy());
      });

      DynamicSparsityPattern dsp(names.relevant);
      DoFTools::make_sparsity_pattern(names.dof_handler, dsp);
      SparsityTools::distribute_sparsity_pattern(dsp,
                                                 names.owned,
                                                 comm,
                                                 names.relevant);
      TrilinosWrappers::SparseMatrix H;
      H.reinit(names.owned, names.owned, dsp, comm);
      TrilinosWrappers::MPI::Vector g(names.owned, comm), alpha(g);
      forms_task.join();
      forms.add_to(H, g);
      H.compress(VectorOperation::add);
      g.compress(VectorOperation::add);
      section.reset();
      result.error_squared_before_optimisation =
        Utilities::MPI::sum(forms.classical_sum(), comm);

      result.optimisation_parameters =
        minimise(H,
                 g,
                 alpha,
                 names,
                 minimisation_method(relaxed, minimisation.tolerance),
                 minimisation,
                 result.error_squared_before_optimisation,
                 result.optimisation_steps,
                 result.exact_minimisation_too_large);
      TrilinosWrappers::MPI::Vector alpha_ghosted(names.owned,
                                                  names.relevant,
                                                  comm);
      alpha_ghosted = alpha;
      if (evaluation == nullptr)
        {
          forms.errors(alpha_ghosted,
                       body.triangulation().n_active_cells(),
                       result);
          return;
        }
      const OptionalTimerSection evaluation_section(
        timer, "error indicator: evaluation");
      const FormInputs evaluation_in{cells,
                                     faces,
                                     evaluation->loads,
                                     u_kinematic,
                                     names,
                                     with_bubbles,
                                     in.couple_allowed};
      errors_at(evaluation_in,
                evaluation->local,
                owned_slots,
                alpha_ghosted,
                body.triangulation().n_active_cells(),
                result);
    }
  } // namespace equilibration
} // namespace coulomb_adapt
