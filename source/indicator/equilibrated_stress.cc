#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/local_neumann_problem.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

namespace coulomb_adapt
{
  namespace
  {
    // A cell of the local mesh (locally owned or ghost) with what the node
    // systems need from it.
    struct CellData
    {
      DoFHandler<2>::active_cell_iterator cell;
      bool                                owned;
      /** Per node k of the scalar base element: the global DoF index of its
       * x component (the node's name on every rank). */
      std::vector<types::global_dof_index> nodes;
      /** Per node k and component c: the global DoF index. */
      std::vector<std::array<types::global_dof_index, 2>> component_dofs;
      /** The nodes' positions. */
      std::vector<Point<2>> points;
      /** int_E sigma_c : eps(phi_k e_c) - f . phi_k e_c, [k][c]. */
      std::vector<std::array<double, 2>> residual;
      /** Local face index of each of the cell's faces. */
      std::vector<unsigned int> faces;
    };

    // A face of the local mesh. Its traction F is sigma^ n of the "plus"
    // cell (the smaller CellId), the other cell sees -F.
    struct FaceData
    {
      int          plus = -1, minus = -1;
      Point<2>     v0, v1;
      Tensor<1, 2> normal; // outward normal of the plus cell
      double       length      = 0;
      bool         at_boundary = false;
      /** Per component: the moments are unknown (interior and Dirichlet
       * edges) rather than prescribed data. */
      std::array<bool, 2> unknown = {{true, true}};
      /** The nodes on the face and their parameter s in [0, 1] along
       * v0 -> v1. */
      std::vector<types::global_dof_index> nodes;
      std::vector<double>                  s;
      /** The nodes' DoF indices per component: the names of the free
       * parameters of their node systems. */
      std::vector<std::array<types::global_dof_index, 2>> node_dofs;
      /** Moments b[node][c], and those of the averaged FE traction. */
      std::vector<std::array<double, 2>> moments, average;
      /** The change of b[node][c] per unit of the free parameter of the
       * node system of (node, c) (0 where that system has none). */
      std::vector<std::array<double, 2>> kernel;
      /** Nodal coefficients of F (degree p, Lagrange in s), and the inverse
       * of the edge mass matrix that maps moments to them. */
      std::vector<std::array<double, 2>> coefficients;
      FullMatrix<double>                 mass_inverse;
      /** Amplitude per component of the edge bubble added to F: the
       * Legendre polynomial of degree p + 1 along the edge, orthogonal to
       * every shape function on it, so that it leaves the moments and the
       * prolongation conditions unchanged (a free parameter of every edge
       * whose tractions are unknown). */
      std::array<double, 2> bubble = {{0., 0.}};
      /** Names of the free parameters in the optimisation's numbering:
       * per node and component (vertices), and of the bubble. */
      std::vector<std::array<types::global_dof_index, 2>> parameter_of_node;
      std::array<types::global_dof_index, 2> parameter_of_bubble = {
        {numbers::invalid_dof_index, numbers::invalid_dof_index}};
    };

    // Lagrange polynomials of the face's nodes at parameter s (p <= 2:
    // at most three nodes; a fixed array, as this is called per
    // quadrature point of every face).
    std::array<double, 3>
    face_shape_values(const std::vector<double> &nodes_s, const double s)
    {
      AssertIndexRange(nodes_s.size(), 4);
      std::array<double, 3> values = {{1., 1., 1.}};
      for (unsigned int k = 0; k < nodes_s.size(); ++k)
        for (unsigned int l = 0; l < nodes_s.size(); ++l)
          if (l != k)
            values[k] *= (s - nodes_s[l]) / (nodes_s[k] - nodes_s[l]);
      return values;
    }

    // The Legendre polynomial of degree n on [0, 1] at s.
    double
    edge_bubble(const unsigned int n, const double s)
    {
      const double x        = 2 * s - 1;
      double       previous = 1, current = x;
      if (n == 0)
        return 1;
      for (unsigned int k = 1; k < n; ++k)
        {
          const double next =
            ((2 * k + 1) * x * current - k * previous) / (k + 1);
          previous = current;
          current  = next;
        }
      return current;
    }

    double
    face_parameter(const FaceData &face, const Point<2> &x)
    {
      const Tensor<1, 2> d = face.v1 - face.v0;
      return (x - face.v0) * d / d.norm_square();
    }


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
    template <typename CellLoad, typename FaceWork>
    void
    optimise_free_parameters(const ElasticBody                   &body,
                             const std::vector<CellData>         &cells,
                             std::vector<FaceData>               &faces,
                             LocalNeumannProblem                 &local,
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

      std::vector<types::global_dof_index> name_dofs(
        names_fe.n_dofs_per_cell());
      double                               before = 0;
      Vector<double>                       load(local.n_coefficients()), base;
      const unsigned int                   M = local.n_coefficients() / 2;
      std::vector<Vector<double>>          direction_loads;
      std::vector<types::global_dof_index> direction_dofs;
      unsigned int                         n_directions = 0;
      FullMatrix<double>                   W;
      std::vector<Vector<double>>          responses;
      std::vector<const Vector<double> *>  loads;
      std::vector<types::global_dof_index> indices;
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        if (cells[slot].owned)
          {
            const auto &cell = cells[slot].cell;
            local.reinit(cell, u_kinematic);
            cell_load(slot, load);
            local.solve(load, base);
            before += local.errors(base)[0];

            const DoFHandler<2>::active_cell_iterator name_cell(&tria,
                                                                cell->level(),
                                                                cell->index(),
                                                                &names);
            name_cell->get_dof_indices(name_dofs);
            const auto name = [&](const unsigned int c, const unsigned int k) {
              return name_dofs[names_fe.component_to_system_index(c, k)];
            };
            // The loads of the cell's free parameters, from the work W of
            // each face's traction basis (the nodal polynomials, then the
            // bubble) on the monomials.
            n_directions = 0;
            const auto direction =
              [&](const types::global_dof_index dof) -> Vector<double> & {
              for (unsigned int i = 0; i < n_directions; ++i)
                if (direction_dofs[i] == dof)
                  return direction_loads[i];
              if (n_directions == direction_loads.size())
                {
                  direction_loads.emplace_back(local.n_coefficients());
                  direction_dofs.push_back(dof);
                }
              direction_dofs[n_directions]  = dof;
              direction_loads[n_directions] = 0;
              return direction_loads[n_directions++];
            };
            for (const unsigned int f : cell->face_indices())
              {
                FaceData          &face   = faces[cells[slot].faces[f]];
                const unsigned int n_face = face.nodes.size();
                face.parameter_of_node.assign(n_face,
                                              {{numbers::invalid_dof_index,
                                                numbers::invalid_dof_index}});
                face_work(slot, face, W);
                for (unsigned int c = 0; c < 2; ++c)
                  {
                    // A vertex's null vector changes F on the faces
                    // through it (moments b[k] += kernel[k]).
                    for (unsigned int k = 0; k < n_face; ++k)
                      if (face.kernel[k][c] != 0)
                        {
                          unsigned int v = 0;
                          while (v < cell->n_vertices() &&
                                 cells[slot].component_dofs[v][c] !=
                                   face.node_dofs[k][c])
                            ++v;
                          Assert(v < cell->n_vertices(), ExcInternalError());
                          face.parameter_of_node[k][c] = name(c, v);
                          Vector<double> &d            = direction(name(c, v));
                          for (unsigned int l = 0; l < n_face; ++l)
                            {
                              const double coefficient =
                                face.mass_inverse(l, k) * face.kernel[k][c];
                              for (unsigned int m = 0; m < M; ++m)
                                d(c * M + m) += coefficient * W(m, l);
                            }
                        }
                    // The edge bubble, named by the edge's DoF.
                    if (with_bubbles && face.unknown[c])
                      {
                        const types::global_dof_index dof =
                          name(c, cell->n_vertices() + f);
                        face.parameter_of_bubble[c] = dof;
                        Vector<double> &d           = direction(dof);
                        for (unsigned int m = 0; m < M; ++m)
                          d(c * M + m) += W(m, n_face);
                      }
                  }
              }
            const unsigned int n = n_directions;
            if (n == 0)
              continue;
            indices.clear();
            responses.resize(n);
            loads.resize(n);
            for (unsigned int i = 0; i < n; ++i)
              {
                local.solve(direction_loads[i], responses[i]);
                loads[i] = &direction_loads[i];
                indices.push_back(direction_dofs[i]);
              }
            // K S_j = l_j (the loads are self-equilibrated), so the energy
            // products are the loads' work: (S_i, S_j) = l_j . S_i.
            FullMatrix<double>  cell_H(n, n);
            std::vector<double> cell_g(n);
            for (unsigned int i = 0; i < n; ++i)
              {
                for (unsigned int j = 0; j <= i; ++j)
                  cell_H(i, j) = cell_H(j, i) = *loads[j] * responses[i];
                cell_g[i] =
                  load * responses[i] - local.kinematic_work(responses[i]);
              }
            H.add(indices, cell_H);
            g.add(indices, cell_g);
          }
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
      if (g_norm == 0)
        return;
      SolverControl                           control(1000, 1e-8 * g_norm);
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
    }
  } // namespace



  EquilibratedStressErrors
  equilibrated_stress_errors(
    const ElasticBody                   &body,
    const TrilinosWrappers::MPI::Vector &u_equilibrium,
    const TrilinosWrappers::MPI::Vector &u_kinematic_in,
    const ContactTractionData           &contact,
    const unsigned int                   degree_increase,
    const bool                           optimise_tractions)
  {
    // Ghosted copies: the node systems read the ghost cells too (the
    // corrected solutions come without ghost entries).
    const MPI_Comm comm = body.triangulation().get_communicator();
    TrilinosWrappers::MPI::Vector u(body.locally_owned_dof_set(),
                                    body.locally_relevant_dof_set(),
                                    comm);
    TrilinosWrappers::MPI::Vector u_kinematic(u);
    u           = u_equilibrium;
    u_kinematic = u_kinematic_in;

    const auto                      &dof_handler = body.dof_handler();
    const FiniteElement<2>          &fe          = dof_handler.get_fe();
    const FiniteElement<2>          &base        = fe.base_element(0);
    const unsigned int               p           = base.degree;
    const unsigned int               n_nodes     = base.n_dofs_per_cell();
    const ElasticMaterial           &material    = body.material();
    const BodyDescription           &description = body.description();
    const FEValuesExtractors::Vector displacement(0);

    // 1. The local cells (owned and ghost) and their element residuals.
    std::vector<CellData>          cells;
    std::map<CellId, unsigned int> slot_of;
    {
      FEValues<2> fe_values(body.mapping(),
                            fe,
                            body.cell_quadrature(),
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
      // The nodes' positions from one FEValues per cell (mapping the
      // support points point by point costs more than the rest).
      FEValues<2>                        support_values(body.mapping(),
                                 fe,
                                 Quadrature<2>(base.get_unit_support_points()),
                                 update_quadrature_points);
      std::vector<SymmetricTensor<2, 2>> strains(fe_values.n_quadrature_points);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          {
            for (const unsigned int f : cell->face_indices())
              AssertThrow(
                cell->at_boundary(f) || (!cell->face(f)->has_children() &&
                                         !cell->neighbor_is_coarser(f)),
                ExcMessage("Error indicator/Estimator = cre: the mesh of " +
                           body.name() +
                           " has hanging nodes. The element equilibration "
                           "is written for conforming meshes: use "
                           "Adaptation/Strategy = remesh or uniform "
                           "(quadrilaterals without a scene's local "
                           "refinement, or triangles)."));
            CellData data;
            data.cell  = cell;
            data.owned = cell->is_locally_owned();
            data.nodes.resize(n_nodes);
            data.component_dofs.resize(n_nodes);
            data.residual.assign(n_nodes, {{0., 0.}});
            cell->get_dof_indices(dofs);
            support_values.reinit(cell);
            data.points = support_values.get_quadrature_points();
            fe_values.reinit(cell);
            fe_values[displacement].get_function_symmetric_gradients(u,
                                                                     strains);
            for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
              {
                const auto [c, k] = fe.system_to_component_index(j);
                if (c == 0)
                  data.nodes[k] = dofs[j];
                data.component_dofs[k][c] = dofs[j];
                double r                  = 0;
                for (const unsigned int q :
                     fe_values.quadrature_point_indices())
                  {
                    double value =
                      material.stress(strains[q]) *
                      fe_values[displacement].symmetric_gradient(j, q);
                    if (description.body_force)
                      value -=
                        fe_values[displacement].value(j, q) *
                        description.body_force(fe_values.quadrature_point(q));
                    r += value * fe_values.JxW(q);
                  }
                data.residual[k][c] = r;
              }
            slot_of[cell->id()] = cells.size();
            cells.push_back(std::move(data));
          }
    }

    // 2. The faces: geometry, orientation, nodes, which moments are known.
    std::map<types::boundary_id, ComponentMask> dirichlet_on;
    for (const auto &d : description.dirichlet)
      dirichlet_on[d.boundary_id] = d.components;
    std::map<types::boundary_id, const TractionFunction *> traction_on;
    for (const auto &t : description.tractions)
      traction_on[t.boundary_id] = &t.traction;

    std::vector<FaceData>                faces;
    std::map<unsigned int, unsigned int> face_of_index;
    for (unsigned int slot = 0; slot < cells.size(); ++slot)
      {
        const auto &cell = cells[slot].cell;
        cells[slot].faces.resize(cell->n_faces());
        for (const unsigned int f : cell->face_indices())
          {
            const unsigned int key = cell->face(f)->index();
            auto [it, inserted]    = face_of_index.emplace(key, faces.size());
            cells[slot].faces[f]   = it->second;
            if (inserted)
              faces.emplace_back();
            FaceData &face = faces[it->second];
            // The plus cell is the one with the smaller CellId.
            const bool becomes_plus =
              face.plus < 0 || cell->id() < cells[face.plus].cell->id();
            if (face.plus >= 0 && !becomes_plus)
              {
                face.minus = slot;
                continue;
              }
            if (face.plus >= 0)
              face.minus = face.plus;
            face.plus      = slot;
            face.v0        = cell->face(f)->vertex(0);
            face.v1        = cell->face(f)->vertex(1);
            face.length    = face.v0.distance(face.v1);
            face.normal[0] = (face.v1 - face.v0)[1] / face.length;
            face.normal[1] = -(face.v1 - face.v0)[0] / face.length;
            if ((cell->face(f)->center() - cell->center()) * face.normal < 0)
              face.normal *= -1;
            face.at_boundary = cell->at_boundary(f);
            if (face.at_boundary)
              {
                const auto d = dirichlet_on.find(cell->face(f)->boundary_id());
                for (unsigned int c = 0; c < 2; ++c)
                  face.unknown[c] = (d != dirichlet_on.end() && d->second[c]);
              }
            face.nodes.clear();
            face.s.clear();
            face.node_dofs.clear();
            // The nodes on the face: support points on its chord (up to
            // the sagitta of a curved face; has_support_on_face() is not
            // precise for every element).
            for (unsigned int k = 0; k < n_nodes; ++k)
              {
                const Point<2> &x = cells[slot].points[k];
                const double    s = face_parameter(face, x);
                const double    distance =
                  x.distance(face.v0 + s * (face.v1 - face.v0));
                if (s > -1e-8 && s < 1 + 1e-8 && distance < 0.05 * face.length)
                  {
                    face.nodes.push_back(cells[slot].nodes[k]);
                    face.node_dofs.push_back(cells[slot].component_dofs[k]);
                    // Vertices at 0 and 1, an edge's middle node at 1/2.
                    face.s.push_back(std::round(2 * s) / 2);
                  }
              }
          }
      }

    // Known moments (loaded, free and contact edges) and the moments of the
    // averaged FE traction on the others. The prescribed traction uses the
    // FE assembly's face quadrature, so that the moments are those of the
    // FE load vector.
    {
      const unsigned int n_face_q = p + 1;
      const QGauss<1>    face_gauss(n_face_q);
      for (auto &face : faces)
        {
          face.moments.assign(face.nodes.size(), {{0., 0.}});
          face.average.assign(face.nodes.size(), {{0., 0.}});
          face.kernel.assign(face.nodes.size(), {{0., 0.}});
          if (!face.at_boundary)
            continue;
          const auto  &cell = cells[face.plus].cell;
          unsigned int f    = 0;
          for (; f < cell->n_faces(); ++f)
            if (cells[face.plus].faces[f] ==
                static_cast<unsigned int>(&face - faces.data()))
              break;
          const auto t = traction_on.find(cell->face(f)->boundary_id());
          if (t != traction_on.end())
            for (unsigned int q = 0; q < face_gauss.size(); ++q)
              {
                const double       s   = face_gauss.point(q)[0];
                const Point<2>     x   = face.v0 + s * (face.v1 - face.v0);
                const Tensor<1, 2> F   = (*t->second)(x, face.normal);
                const auto         phi = face_shape_values(face.s, s);
                for (unsigned int k = 0; k < face.nodes.size(); ++k)
                  for (unsigned int c = 0; c < 2; ++c)
                    face.moments[k][c] +=
                      F[c] * phi[k] * face_gauss.weight(q) * face.length;
              }
        }
      // The contact traction, on the face of its cell that holds the point.
      for (const auto &[id, points] : contact)
        {
          const auto slot = slot_of.find(id);
          if (slot == slot_of.end())
            continue;
          for (const auto &point : points)
            {
              double       best = 1e300;
              unsigned int face = 0;
              for (const unsigned int fi : cells[slot->second].faces)
                if (faces[fi].at_boundary)
                  {
                    const double s =
                      std::clamp(face_parameter(faces[fi], point.point),
                                 0.,
                                 1.);
                    const double d = point.point.distance(
                      faces[fi].v0 + s * (faces[fi].v1 - faces[fi].v0));
                    if (d < best)
                      best = d, face = fi;
                  }
              const auto phi =
                face_shape_values(faces[face].s,
                                  face_parameter(faces[face], point.point));
              for (unsigned int k = 0; k < faces[face].nodes.size(); ++k)
                for (unsigned int c = 0; c < 2; ++c)
                  if (!faces[face].unknown[c])
                    faces[face].moments[k][c] +=
                      point.traction[c] * phi[k] * point.weight;
            }
        }

      // Averaged traction 1/2 (sigma_c|E+ + sigma_c|E-) n+ (the one side's
      // on Dirichlet edges), from each side's own face quadrature.
      FEFaceValues<2>                    face_values(body.mapping(),
                                  fe,
                                  QGauss<1>(p + 1),
                                  update_gradients | update_quadrature_points |
                                    update_JxW_values);
      std::vector<SymmetricTensor<2, 2>> strains(
        face_values.n_quadrature_points);
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        for (const unsigned int f : cells[slot].cell->face_indices())
          {
            FaceData &face = faces[cells[slot].faces[f]];
            if ((face.at_boundary && !face.unknown[0] && !face.unknown[1]) ||
                (!face.at_boundary && (face.plus < 0 || face.minus < 0)))
              continue;
            const double weight = face.at_boundary ? 1. : 0.5;
            face_values.reinit(cells[slot].cell, f);
            face_values[displacement].get_function_symmetric_gradients(u,
                                                                       strains);
            for (const unsigned int q : face_values.quadrature_point_indices())
              {
                const Tensor<1, 2> F =
                  material.stress(strains[q]) * face.normal;
                const auto phi = face_shape_values(
                  face.s,
                  face_parameter(face, face_values.quadrature_point(q)));
                for (unsigned int k = 0; k < face.nodes.size(); ++k)
                  for (unsigned int c = 0; c < 2; ++c)
                    face.average[k][c] +=
                      weight * F[c] * phi[k] * face_values.JxW(q);
              }
          }
    }

    // 3. The node systems, for every node of a locally owned cell (its
    // star is then all local: the ghost layer holds every cell that shares
    // a vertex with an owned cell).
    EquilibratedStressErrors result;
    {
      std::map<types::global_dof_index,
               std::vector<std::pair<unsigned int, unsigned int>>>
        star; // node -> (cell slot, local node)
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        for (unsigned int k = 0; k < n_nodes; ++k)
          star[cells[slot].nodes[k]].emplace_back(slot, k);
      std::set<types::global_dof_index> owned_nodes;
      for (const auto &cell : cells)
        if (cell.owned)
          owned_nodes.insert(cell.nodes.begin(), cell.nodes.end());

      double largest_residual = 0;
      for (const auto &cell : cells)
        for (const auto &r : cell.residual)
          largest_residual =
            std::max({largest_residual, std::abs(r[0]), std::abs(r[1])});

      for (const auto node : owned_nodes)
        {
          auto &cells_of_node = star[node];
          std::sort(cells_of_node.begin(),
                    cells_of_node.end(),
                    [&](const auto &a, const auto &b) {
                      return cells[a.first].cell->id() <
                             cells[b.first].cell->id();
                    });
          // The faces of the star through the node, and the node's place
          // on each.
          std::vector<std::pair<unsigned int, unsigned int>> node_faces;
          for (const auto &[slot, k] : cells_of_node)
            for (const unsigned int fi : cells[slot].faces)
              {
                const auto &nodes = faces[fi].nodes;
                const auto  where = std::find(nodes.begin(), nodes.end(), node);
                if (where != nodes.end() &&
                    std::find_if(node_faces.begin(),
                                 node_faces.end(),
                                 [fi = fi](const auto &e) {
                                   return e.first == fi;
                                 }) == node_faces.end())
                  node_faces.emplace_back(fi, where - nodes.begin());
              }

          for (unsigned int c = 0; c < 2; ++c)
            {
              std::vector<unsigned int> columns; // index into node_faces
              for (unsigned int e = 0; e < node_faces.size(); ++e)
                if (faces[node_faces[e].first].unknown[c])
                  columns.push_back(e);
              const unsigned int n_rows = cells_of_node.size();
              const unsigned int n_cols = columns.size();
              FullMatrix<double> A(n_rows, n_cols);
              Vector<double>     r(n_rows);
              for (unsigned int row = 0; row < n_rows; ++row)
                {
                  const auto [slot, k] = cells_of_node[row];
                  r(row)               = cells[slot].residual[k][c];
                  for (unsigned int e = 0; e < node_faces.size(); ++e)
                    {
                      const FaceData &face = faces[node_faces[e].first];
                      const int       sign =
                        face.plus == static_cast<int>(slot)  ? 1 :
                              face.minus == static_cast<int>(slot) ? -1 :
                                                                     0;
                      if (sign == 0)
                        continue;
                      const auto col =
                        std::find(columns.begin(), columns.end(), e);
                      if (col != columns.end())
                        A(row, col - columns.begin()) = sign;
                      else
                        r(row) -= sign * face.moments[node_faces[e].second][c];
                    }
                }
              if (n_cols == 0)
                {
                  result.node_system_defect =
                    std::max(result.node_system_defect, r.linfty_norm());
                  continue;
                }
              // x = b_avg + A^+ (r - A b_avg): the least-squares solution
              // closest to the averaged moments (A^+ from the SVD; the
              // systems of interior nodes are singular by one).
              Vector<double> x0(n_cols), rhs(n_rows), y(n_cols);
              for (unsigned int j = 0; j < n_cols; ++j)
                {
                  const auto &e = node_faces[columns[j]];
                  x0(j)         = faces[e.first].average[e.second][c];
                }
              A.vmult(rhs, x0);
              rhs.sadd(-1., 1., r);
              // Closest in sum |G| (F - F_avg)^2 ~ sum (b - b_avg)^2 / |G|:
              // columns scaled by sqrt|G|.
              std::vector<double> scale(n_cols);
              for (unsigned int j = 0; j < n_cols; ++j)
                scale[j] =
                  std::sqrt(faces[node_faces[columns[j]].first].length);
              LAPACKFullMatrix<double> svd(n_rows, n_cols);
              for (unsigned int row = 0; row < n_rows; ++row)
                for (unsigned int j = 0; j < n_cols; ++j)
                  svd(row, j) = A(row, j) * scale[j];
              svd.compute_svd();
              const auto &U  = svd.get_svd_u();
              const auto &Vt = svd.get_svd_vt();
              for (unsigned int i = 0; i < std::min(n_rows, n_cols); ++i)
                if (svd.singular_value(i) > 1e-10 * svd.singular_value(0))
                  {
                    double coefficient = 0;
                    for (unsigned int row = 0; row < n_rows; ++row)
                      coefficient += U(row, i) * rhs(row);
                    coefficient /= svd.singular_value(i);
                    for (unsigned int j = 0; j < n_cols; ++j)
                      y(j) += coefficient * Vt(i, j) * scale[j];
                  }
              // The free parameter: the first null vector of the scaled
              // matrix (one per interior or Dirichlet node), mapped back
              // to moments. Every rank that solves this node system finds
              // the same one (same star, same order).
              unsigned int rank = 0;
              while (rank < std::min(n_rows, n_cols) &&
                     svd.singular_value(rank) > 1e-10 * svd.singular_value(0))
                ++rank;
              if (rank < n_cols)
                {
                  double largest = 0;
                  for (unsigned int j = 0; j < n_cols; ++j)
                    largest =
                      std::max(largest, std::abs(Vt(rank, j) * scale[j]));
                  for (unsigned int j = 0; j < n_cols; ++j)
                    {
                      const auto &e = node_faces[columns[j]];
                      faces[e.first].kernel[e.second][c] =
                        Vt(rank, j) * scale[j] / largest;
                    }
                }
              Vector<double> defect(n_rows);
              A.vmult(defect, y);
              defect -= rhs;
              result.node_system_defect =
                std::max(result.node_system_defect, defect.linfty_norm());
              for (unsigned int j = 0; j < n_cols; ++j)
                {
                  const auto &e                       = node_faces[columns[j]];
                  faces[e.first].moments[e.second][c] = x0(j) + y(j);
                }
            }
        }
      if (largest_residual > 0)
        result.node_system_defect /= largest_residual;
    }

    // 4. F on each face: the polynomial of degree p with the face's
    // moments (the inverse edge mass matrix on the chord).
    const auto update_coefficients = [](FaceData &face) {
      const unsigned int n = face.nodes.size();
      face.coefficients.assign(n, {{0., 0.}});
      if (face.plus < 0 || (!face.unknown[0] && !face.unknown[1]))
        return;
      for (unsigned int k = 0; k < n; ++k)
        for (unsigned int l = 0; l < n; ++l)
          for (unsigned int c = 0; c < 2; ++c)
            face.coefficients[k][c] +=
              face.mass_inverse(k, l) * face.moments[l][c];
    };
    {
      const QGauss<1> gauss(p + 1);
      for (auto &face : faces)
        {
          const unsigned int n = face.nodes.size();
          face.mass_inverse.reinit(n, n);
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              const auto phi = face_shape_values(face.s, gauss.point(q)[0]);
              for (unsigned int k = 0; k < n; ++k)
                for (unsigned int l = 0; l < n; ++l)
                  face.mass_inverse(k, l) +=
                    phi[k] * phi[l] * gauss.weight(q) * face.length;
            }
          if (n > 0)
            face.mass_inverse.gauss_jordan();
          update_coefficients(face);
        }
    }

    // The loads of the local problems. A face's traction eta F with the
    // given nodal coefficients, on the components in mask:
    LocalNeumannProblem local(body, p + degree_increase);
    const QGauss<1>     edge_rule(p + degree_increase + 2);
    const auto          add_face_load =
      [&](Vector<double>                           &load,
          const unsigned int                        slot,
          const FaceData                           &face,
          const std::vector<std::array<double, 2>> &coefficients,
          const std::array<double, 2>              &bubble,
          const std::array<bool, 2>                &mask) {
        const double eta = face.plus == static_cast<int>(slot) ? 1 : -1;
        for (unsigned int q = 0; q < edge_rule.size(); ++q)
          {
            const double s   = edge_rule.point(q)[0];
            const auto   phi = face_shape_values(face.s, s);
            Tensor<1, 2> F;
            for (unsigned int k = 0; k < face.nodes.size(); ++k)
              for (unsigned int c = 0; c < 2; ++c)
                F[c] += phi[k] * coefficients[k][c];
            const double L = edge_bubble(p + 1, s);
            for (unsigned int c = 0; c < 2; ++c)
              F[c] += bubble[c] * L;
            local.add_traction(load,
                               face.v0 + s * (face.v1 - face.v0),
                               eta * F,
                               edge_rule.weight(q) * face.length,
                               mask);
          }
      };
    // The work W(m, j) of the face's traction basis j (its nodal
    // polynomials, then the bubble), with the cell's orientation eta, on
    // monomial m of the cell's local problem.
    const auto face_work = [&](const unsigned int  slot,
                               const FaceData     &face,
                               FullMatrix<double> &W) {
      const unsigned int n   = face.nodes.size();
      const unsigned int M   = local.n_coefficients() / 2;
      const double       eta = face.plus == static_cast<int>(slot) ? 1 : -1;
      W.reinit(M, n + 1);
      for (unsigned int q = 0; q < edge_rule.size(); ++q)
        {
          const double s   = edge_rule.point(q)[0];
          const auto   phi = face_shape_values(face.s, s);
          const double L   = edge_bubble(p + 1, s);
          const double w   = eta * edge_rule.weight(q) * face.length;
          const auto  &values =
            local.monomial_values(face.v0 + s * (face.v1 - face.v0));
          for (unsigned int m = 0; m < M; ++m)
            {
              for (unsigned int j = 0; j < n; ++j)
                W(m, j) += phi[j] * values[m] * w;
              W(m, n) += L * values[m] * w;
            }
        }
    };
    // ... and the whole load of a cell: the body force, eta F where the
    // moments were solved for, the prescribed data elsewhere, and the
    // contact traction. local must be reinit'ed on the cell.
    const auto cell_load = [&](const unsigned int slot, Vector<double> &load) {
      const auto &cell = cells[slot].cell;
      load             = local.body_force_load();
      for (const unsigned int f : cell->face_indices())
        {
          const FaceData           &face   = faces[cells[slot].faces[f]];
          const std::array<bool, 2> solved = {
            {face.unknown[0], face.unknown[1]}};
          if (solved[0] || solved[1])
            add_face_load(
              load, slot, face, face.coefficients, face.bubble, solved);
          const std::array<bool, 2> prescribed = {{!solved[0], !solved[1]}};
          if (face.at_boundary && (prescribed[0] || prescribed[1]))
            {
              const auto t = traction_on.find(cell->face(f)->boundary_id());
              if (t != traction_on.end())
                for (unsigned int q = 0; q < edge_rule.size(); ++q)
                  {
                    const Point<2> x =
                      face.v0 + edge_rule.point(q)[0] * (face.v1 - face.v0);
                    local.add_traction(load,
                                       x,
                                       (*t->second)(x, face.normal),
                                       edge_rule.weight(q) * face.length,
                                       prescribed);
                  }
            }
        }
      if (const auto c = contact.find(cell->id()); c != contact.end())
        for (const auto &point : c->second)
          local.add_traction(
            load, point.point, point.traction, point.weight, {{true, true}});
    };

    // 5. The free parameters of the node systems (one per interior or
    // Dirichlet node and component) chosen to minimise the estimate
    // sum_E ||sigma^ - sigma_c||^2 itself, instead of the distance to the
    // averaged traction: sigma^ is affine in them, so this is one sparse
    // symmetric positive definite system with the pattern of the
    // stiffness matrix. Any value of the parameters keeps sigma^
    // statically admissible, so an inexact solve only makes the bound
    // less tight.
    if (optimise_tractions)
      optimise_free_parameters(body,
                               cells,
                               faces,
                               local,
                               u_kinematic,
                               cell_load,
                               face_work,
                               // A bubble of degree p + 1 needs local
                               // problems of degree p + 3 to be resolved:
                               // with p + 2 the minimisation finds the
                               // local problems' blind spots (Q2: an
                               // estimate below the exact error).
                               degree_increase >= 3,
                               result);
    for (auto &face : faces)
      update_coefficients(face);

    // 6. The local Neumann problems and the errors, cell by cell.
    result.error_squared.reinit(body.triangulation().n_active_cells());
    double         sum_norm = 0;
    Vector<double> load(local.n_coefficients()), coefficients;
    for (unsigned int slot = 0; slot < cells.size(); ++slot)
      if (cells[slot].owned)
        {
          local.reinit(cells[slot].cell, u_kinematic);
          cell_load(slot, load);
          result.local_problem_defect =
            std::max(result.local_problem_defect,
                     local.solve(load, coefficients));
          const auto errors = local.errors(coefficients);
          result.error_squared(cells[slot].cell->active_cell_index()) =
            errors[0];
          sum_norm += errors[1];
        }

    result.sum_norm_squared = Utilities::MPI::sum(sum_norm, comm);
    if (!optimise_tractions)
      result.error_squared_before_optimisation =
        Utilities::MPI::sum(result.error_squared.l1_norm(), comm);
    result.node_system_defect =
      Utilities::MPI::max(result.node_system_defect, comm);
    result.local_problem_defect =
      Utilities::MPI::max(result.local_problem_defect, comm);
    return result;
  }
} // namespace coulomb_adapt
