// Superconvergent patch recovery (SPR, Zienkiewicz and Zhu 1992) of the
// stress of one body, in parallel.
//
// For every vertex (the patch centre) a polynomial of degree p per stress
// component is fitted, in the least-squares sense, to the raw stress
// K eps(u_h) at the sampling points of the cells around the vertex: the
// Gauss points of order p (superconvergent for quadrilaterals; the usual
// choice for triangles). Nodal values of the recovered field then come
// from these polynomials:
//  - an interior vertex takes the value of its own polynomial;
//  - a boundary vertex, or an interior one whose patch does not determine
//    a degree-p polynomial, takes the average of the polynomials of the
//    interior patches it belongs to (ZZ's treatment of boundaries);
//  - an edge node (p = 2) averages the patches of the edge's end vertices,
//    a cell node (Q2) those of the cell's vertices;
//  - hanging nodes follow from the hanging-node constraints.
//
// The normal equations of a patch are sums of per-cell terms. Each rank
// adds the terms of its own cells into a distributed vector with one slot
// per vertex and entry (vertex k, entry e at k * n_entries + e, the
// vertices numbered by a scalar linear DoFHandler), and a compress(add)
// leaves the complete sums with the vertex's owner. The owner solves the small
// system; a ghost update then gives every rank the polynomials of all vertices
// of its cells and ghost cells, which is all a node of an owned cell needs. No
// cell beyond the ghost layer is ever used, and the result does not depend on
// the partition (up to the order of floating-point sums).

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <coulomb_adapt/indicator/recovered_stress.h>
#include <coulomb_adapt/indicator/spr_patch_fit.h>

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  using namespace spr;



  namespace
  {
    using VertexCell = DoFHandler<2>::active_cell_iterator;

    // A vertex and the cells around it, as far as this rank sees them:
    // complete for every vertex of a locally owned cell, since the ghost
    // layer holds all cells sharing a vertex with an owned cell.
    struct VertexPatch
    {
      /** The vertex's number in the vertex DoFHandler. */
      types::global_dof_index vertex = numbers::invalid_dof_index;
      Point<2>                location;
      std::vector<VertexCell> cells;
      bool                    at_boundary = false;
    };



    // The position of vertex @p k among @p relevant_vertices, where the
    // per-vertex patches and fits are stored.
    std::size_t
    relevant_position(const IndexSet               &relevant_vertices,
                      const types::global_dof_index k)
    {
      const auto position = relevant_vertices.index_within_set(k);
      Assert(position != numbers::invalid_dof_index,
             ExcMessage("SPR: a vertex outside the ghost layer."));
      return position;
    }



    // The entries of the vertices in @p vertices: vertex k owns the
    // indices k * n_entries ... (k + 1) * n_entries - 1.
    IndexSet
    vertex_entries(const IndexSet &vertices, const unsigned int n_entries)
    {
      IndexSet entries(vertices.size() * n_entries);
      for (auto interval = vertices.begin_intervals();
           interval != vertices.end_intervals();
           ++interval)
        entries.add_range(*interval->begin() * n_entries,
                          (interval->last() + 1) * n_entries);
      entries.compress();
      return entries;
    }

    // The patches of all vertices of the locally owned and ghost cells
    // (the locally relevant vertices), at the vertex's position in
    // @p relevant_vertices.
    std::vector<VertexPatch>
    collect_vertex_patches(const DoFHandler<2> &vertex_dofs,
                           const IndexSet      &relevant_vertices)
    {
      std::vector<VertexPatch> patches(relevant_vertices.n_elements());
      const auto               patch_of =
        [&](const types::global_dof_index vertex) -> VertexPatch & {
        return patches[relevant_position(relevant_vertices, vertex)];
      };
      for (const auto &cell : vertex_dofs.active_cell_iterators())
        if (!cell->is_artificial())
          {
            for (const unsigned int v : cell->vertex_indices())
              {
                VertexPatch &patch = patch_of(cell->vertex_dof_index(v, 0));
                if (patch.cells.empty())
                  {
                    patch.vertex   = cell->vertex_dof_index(v, 0);
                    patch.location = cell->vertex(v);
                    // One allocation per vertex for the usual valence
                    // (6 triangles, 4 quadrilaterals; more after
                    // refinement), instead of one per doubling.
                    patch.cells.reserve(2 * cell->n_vertices());
                  }
                patch.cells.push_back(cell);
              }
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary())
                for (const unsigned int v : face->vertex_indices())
                  patch_of(face->vertex_dof_index(v, 0)).at_boundary = true;
          }
      return patches;
    }



    // The raw stress at the sampling points of the locally owned cells
    // (@p sampled, with the points' positions), added into the normal
    // equations of each of the cell's vertices (in coordinates relative to
    // that vertex).
    void
    add_cell_contributions(
      const QuadratureStress                     &sampled,
      const DoFHandler<2>                        &vertex_dofs,
      const PatchLayout                          &layout,
      LinearAlgebra::distributed::Vector<double> &normal_equations)
    {
      const unsigned int  n = layout.n_fit_monomials();
      std::vector<double> cell_entries(layout.n_entries());
      unsigned int        owned_cell = 0;
      for (const auto &cell : vertex_dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            for (const unsigned int v : cell->vertex_indices())
              {
                std::fill(cell_entries.begin(), cell_entries.end(), 0.);
                for (unsigned int q = 0; q < sampled.n_points(); ++q)
                  {
                    const Tensor<1, 3> &sigma = sampled.stress(owned_cell, q);
                    const auto          m =
                      monomials(sampled.point(owned_cell, q) - cell->vertex(v));
                    for (unsigned int i = 0; i < n; ++i)
                      {
                        for (unsigned int j = i; j < n; ++j)
                          cell_entries[layout.matrix_entry(i, j)] +=
                            m[i] * m[j];
                        for (unsigned int c = 0; c < 3; ++c)
                          cell_entries[layout.rhs_entry(c, i)] +=
                            m[i] * sigma[c];
                      }
                  }
                const auto first_entry =
                  cell->vertex_dof_index(v, 0) * layout.n_entries();
                for (unsigned int e = 0; e < layout.n_entries(); ++e)
                  normal_equations(first_entry + e) += cell_entries[e];
              }
            ++owned_cell;
          }
      AssertDimension(owned_cell, sampled.n_cells());
      normal_equations.compress(VectorOperation::add);
    }



    // Fit the patch of every locally owned vertex and store the result.
    // Hanging vertices are no patch centres: their cells lie on one side
    // only, and their values come from the constraints anyway.
    void
    fit_owned_patches(
      const std::vector<VertexPatch>                   &patches,
      const LinearAlgebra::distributed::Vector<double> &normal_equations,
      const AffineConstraints<double>                  &hanging_vertices,
      const PatchLayout                                &layout,
      const unsigned int                                degree,
      LinearAlgebra::distributed::Vector<double>       &fits)
    {
      const IndexSet     &owned = fits.get_partitioner()->locally_owned_range();
      std::vector<double> entries(layout.n_entries());
      for (const VertexPatch &patch : patches)
        if (!patch.cells.empty() &&
            owned.is_element(patch.vertex * layout.n_entries()) &&
            !hanging_vertices.is_constrained(patch.vertex))
          {
            const auto dof = [&](const unsigned int e) {
              return patch.vertex * layout.n_entries() + e;
            };
            for (unsigned int e = 0; e < layout.n_entries(); ++e)
              entries[e] = normal_equations(dof(e));
            const PatchFit fit =
              fit_patch(entries, layout, degree, patch.location);
            if (!fit.has_fit)
              continue;
            for (unsigned int k = 0; k < n_monomials(fit.degree); ++k)
              for (unsigned int c = 0; c < 3; ++c)
                fits(dof(layout.coefficient_entry(c, k))) =
                  fit.coefficients[k][c];
            fits(dof(layout.fitted_degree_entry())) = fit.degree + 1;
            fits(dof(layout.is_centre_entry())) =
              (!patch.at_boundary && fit.degree == degree) ? 1. : 0.;
          }
      fits.update_ghost_values();
    }



    // The fits of all vertices this rank sees, from the ghosted vector, in
    // the order of @p patches.
    std::vector<PatchFit>
    read_fits(const std::vector<VertexPatch>                   &patches,
              const LinearAlgebra::distributed::Vector<double> &fits,
              const PatchLayout                                &layout)
    {
      std::vector<PatchFit> result;
      result.reserve(patches.size());
      for (const VertexPatch &patch : patches)
        {
          PatchFit fit;
          if (patch.cells.empty())
            {
              // Not a vertex of this rank's cells: never read.
              result.push_back(fit);
              continue;
            }
          const auto dof = [&](const unsigned int e) {
            return patch.vertex * layout.n_entries() + e;
          };
          fit.centre = patch.location;
          const double degree_plus_one =
            fits(dof(layout.fitted_degree_entry()));
          fit.has_fit   = degree_plus_one > 0.5;
          fit.degree    = fit.has_fit ? std::lround(degree_plus_one) - 1 : 0;
          fit.is_centre = fits(dof(layout.is_centre_entry())) > 0.5;
          for (unsigned int k = 0; k < n_monomials(fit.degree); ++k)
            for (unsigned int c = 0; c < 3; ++c)
              fit.coefficients[k][c] =
                fits(dof(layout.coefficient_entry(c, k)));
          result.push_back(fit);
        }
      return result;
    }



    // The recovered stress at node x, from the patches it belongs to: the
    // SPR centres among its own vertices (the vertex itself, the edge's end
    // vertices, the cell's vertices), else the SPR centres among the
    // vertices of all cells containing it, the way ZZ treat boundary
    // nodes. On meshes too coarse for that (no interior vertex nearby) the
    // best fits the own vertices' patches allow (lower degree) are used.
    // @p collect_surrounding gives the vertices of the cells containing the
    // node; it is called only if no own vertex is a centre (nodes on or
    // next to the boundary): for the others the set would be wasted work.
    template <typename OwnVertices, typename CollectSurrounding>
    Tensor<1, 3>
    node_value(const Point<2>              &x,
               const OwnVertices           &own_vertices,
               const CollectSurrounding    &collect_surrounding,
               const std::vector<PatchFit> &fits,
               const IndexSet              &relevant_vertices)
    {
      const auto average = [&](const auto   &vertices,
                               const bool    centres_only,
                               Tensor<1, 3> &sigma) {
        sigma                = Tensor<1, 3>();
        unsigned int n_found = 0;
        for (const auto v : vertices)
          {
            const PatchFit &fit = fits[relevant_position(relevant_vertices, v)];
            if (centres_only ? fit.is_centre : fit.has_fit)
              {
                sigma += fit.value(x);
                ++n_found;
              }
          }
        if (n_found > 0)
          sigma /= n_found;
        return n_found > 0;
      };

      Tensor<1, 3> sigma;
      if (average(own_vertices, true, sigma))
        return sigma;
      const std::set<types::global_dof_index> surrounding =
        collect_surrounding();
      if (average(surrounding, true, sigma) ||
          average(own_vertices, false, sigma) ||
          average(surrounding, false, sigma))
        return sigma;
      AssertThrow(false,
                  ExcMessage("SPR: no patch fit for the node at (" +
                             std::to_string(x[0]) + ", " +
                             std::to_string(x[1]) + ")."));
      return sigma;
    }



    // One DoF per vertex: the numbering of the distributed per-vertex data
    // (its hanging-node constraints mark the hanging vertices). A scalar
    // linear element, not an FESystem with one component per entry: the
    // entries of vertex k are k * n_entries + e (vertex_entries), so DoF
    // distribution and the DoF lookups per cell do not grow with the
    // number of entries. For p = 1 the stress space is that element
    // already; p = 2 needs one of its own.
    class VertexNumbering
    {
    public:
      VertexNumbering(const ElasticBody               &body,
                      const unsigned int               degree,
                      const DoFHandler<2>             &stress_dofs,
                      const IndexSet                  &stress_relevant,
                      const AffineConstraints<double> &stress_hanging)
        : dofs(&stress_dofs)
        , relevant(&stress_relevant)
        , hanging(&stress_hanging)
      {
        if (degree == 1)
          return;
        linear_dofs.reinit(body.triangulation());
        if (body.is_simplex_mesh())
          linear_dofs.distribute_dofs(FE_SimplexP<2>(1));
        else
          linear_dofs.distribute_dofs(FE_Q<2>(1));
        DoFTools::extract_locally_relevant_dofs(linear_dofs, linear_relevant);
        linear_hanging.reinit(linear_relevant);
        DoFTools::make_hanging_node_constraints(linear_dofs, linear_hanging);
        linear_hanging.close();
        dofs     = &linear_dofs;
        relevant = &linear_relevant;
        hanging  = &linear_hanging;
      }

      const DoFHandler<2>             *dofs;
      const IndexSet                  *relevant;
      const AffineConstraints<double> *hanging;

    private:
      DoFHandler<2>             linear_dofs;
      IndexSet                  linear_relevant;
      AffineConstraints<double> linear_hanging;
    };



    void
    insert_vertices(const VertexCell &c, std::set<types::global_dof_index> &set)
    {
      for (const unsigned int v : c->vertex_indices())
        set.insert(c->vertex_dof_index(v, 0));
    }



    // node_value for each kind of node of the stress space: a vertex, a
    // node on a line, a node inside a cell. A vertex, a line's two or a
    // cell's three or four own vertices: on the stack, this runs once per
    // node.
    struct NodeRecovery
    {
      using OwnVertices =
        boost::container::small_vector<types::global_dof_index, 4>;

      Tensor<1, 3>
      at_vertex(const Point<2> &x, const types::global_dof_index vertex) const
      {
        const OwnVertices own_vertices = {vertex};
        const auto        surrounding  = [&]() {
          std::set<types::global_dof_index> set;
          for (const auto &c :
               patches[relevant_position(relevant_vertices, vertex)].cells)
            insert_vertices(c, set);
          return set;
        };
        return node_value(
          x, own_vertices, surrounding, fits, relevant_vertices);
      }

      // In 2D the lines of a cell are its faces.
      Tensor<1, 3>
      on_line(const Point<2> &x, const DoFHandler<2>::face_iterator &line) const
      {
        const OwnVertices own_vertices = {line->vertex_dof_index(0, 0),
                                          line->vertex_dof_index(1, 0)};
        const auto        surrounding  = [&]() {
          std::set<types::global_dof_index> set;
          for (const auto &c :
               patches[relevant_position(relevant_vertices, own_vertices[0])]
                 .cells)
            for (const unsigned int v : c->vertex_indices())
              if (c->vertex_dof_index(v, 0) == own_vertices[1])
                insert_vertices(c, set);
          return set;
        };
        return node_value(
          x, own_vertices, surrounding, fits, relevant_vertices);
      }

      Tensor<1, 3>
      inside_cell(const Point<2> &x, const VertexCell &cell) const
      {
        OwnVertices own_vertices;
        for (const unsigned int v : cell->vertex_indices())
          own_vertices.push_back(cell->vertex_dof_index(v, 0));
        const auto surrounding = [&]() {
          std::set<types::global_dof_index> set;
          insert_vertices(cell, set);
          return set;
        };
        return node_value(
          x, own_vertices, surrounding, fits, relevant_vertices);
      }

      const std::vector<VertexPatch> &patches;
      const std::vector<PatchFit>    &fits;
      const IndexSet                 &relevant_vertices;
    };



    // Nodal values of the owned, unconstrained nodes of the stress space
    // (@p dofs with element @p fe), at the nodes' physical positions. The
    // vertex nodes (all of them for p = 1) sit at the cell's vertices,
    // which every mapping keeps; only the nodes on lines and inside cells
    // need the mapping. Only owned entries are written; the constrained
    // ones and the ghosts are left to the caller.
    void
    set_owned_nodal_values(
      const ElasticBody                          &body,
      const FiniteElement<2>                     &fe,
      const DoFHandler<2>                        &dofs,
      const IndexSet                             &owned_dofs,
      const AffineConstraints<double>            &constraints,
      const DoFHandler<2>                        &vertex_dofs,
      const NodeRecovery                         &recovery,
      std::array<RecoveredStress::VectorType, 3> &components)
    {
      const bool only_vertex_nodes =
        fe.n_dofs_per_cell() ==
        fe.reference_cell().n_vertices() * fe.n_dofs_per_vertex();
      std::optional<FEValues<2>> node_positions;
      if (!only_vertex_nodes)
        node_positions.emplace(body.mapping(),
                               fe,
                               Quadrature<2>(fe.get_unit_support_points()),
                               update_quadrature_points);
      std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
      std::vector<bool>                    done(owned_dofs.n_elements(), false);
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dof_indices);
            if (node_positions)
              node_positions->reinit(cell);
            const VertexCell   vertex_cell(&body.triangulation(),
                                         cell->level(),
                                         cell->index(),
                                         &vertex_dofs);
            const unsigned int first_line_node =
              cell->n_vertices() * fe.n_dofs_per_vertex();
            const unsigned int first_interior_node =
              first_line_node + cell->n_lines() * fe.n_dofs_per_line();
            for (unsigned int node = 0; node < fe.n_dofs_per_cell(); ++node)
              {
                const auto dof = dof_indices[node];
                if (!owned_dofs.is_element(dof) ||
                    constraints.is_constrained(dof) ||
                    done[owned_dofs.index_within_set(dof)])
                  continue;
                done[owned_dofs.index_within_set(dof)] = true;

                const Point<2> &x =
                  node < first_line_node ?
                    cell->vertex(node / fe.n_dofs_per_vertex()) :
                    node_positions->quadrature_point(node);
                Tensor<1, 3> sigma;
                if (node < first_line_node)
                  sigma =
                    recovery.at_vertex(x,
                                       vertex_cell->vertex_dof_index(
                                         node / fe.n_dofs_per_vertex(), 0));
                else if (node < first_interior_node)
                  sigma = recovery.on_line(x,
                                           vertex_cell->face(
                                             (node - first_line_node) /
                                             fe.n_dofs_per_line()));
                else
                  sigma = recovery.inside_cell(x, vertex_cell);
                for (unsigned int c = 0; c < 3; ++c)
                  components[c](dof) = sigma[c];
              }
          }
    }
  } // namespace



  void
  RecoveredStress::recover_spr(
    const TrilinosWrappers::MPI::Vector &displacement)
  {
    const unsigned int degree = fe.degree;
    AssertThrow(degree >= 1 && degree <= max_spr_degree,
                ExcMessage("'Error indicator/Recovery = spr' supports "
                           "polynomial degrees 1 and 2, not " +
                           std::to_string(degree) + "; use 'zz'."));
    const PatchLayout layout(degree);
    const MPI_Comm    comm    = body.triangulation().get_communicator();
    const bool        simplex = body.is_simplex_mesh();

    const VertexNumbering numbering(
      body, degree, dofs, relevant_dofs, constraints);
    const DoFHandler<2>             &vertex_dofs       = *numbering.dofs;
    const IndexSet                  &relevant_vertices = *numbering.relevant;
    const AffineConstraints<double> &hanging_vertices  = *numbering.hanging;
    const IndexSet                   owned_entries =
      vertex_entries(vertex_dofs.locally_owned_dofs(), layout.n_entries());
    const IndexSet relevant_entries =
      vertex_entries(relevant_vertices, layout.n_entries());

    // Gauss points of order p: the cell centroid for Q1 and P1, the 2 x 2
    // points of Q2, the 3-point rule of P2.
    const Quadrature<2> sampling_points =
      simplex ? static_cast<Quadrature<2>>(QGaussSimplex<2>(degree)) :
                static_cast<Quadrature<2>>(QGauss<2>(degree));

    LinearAlgebra::distributed::Vector<double> normal_equations(
      owned_entries, relevant_entries, comm);
    add_cell_contributions(
      QuadratureStress(body, displacement, sampling_points, true),
      vertex_dofs,
      layout,
      normal_equations);

    const auto patches = collect_vertex_patches(vertex_dofs, relevant_vertices);
    // The same layout: share the partitioner (set up with MPI).
    LinearAlgebra::distributed::Vector<double> fit_vector;
    fit_vector.reinit(normal_equations);
    fit_owned_patches(
      patches, normal_equations, hanging_vertices, layout, degree, fit_vector);
    const auto fits = read_fits(patches, fit_vector, layout);

    for (auto &v : components)
      v = 0;
    set_owned_nodal_values(body,
                           fe,
                           dofs,
                           owned_dofs,
                           constraints,
                           vertex_dofs,
                           NodeRecovery{patches, fits, relevant_vertices},
                           components);
    for (auto &v : components)
      {
        constraints.distribute(v);
        v.update_ghost_values();
      }
  }
} // namespace coulomb_adapt
