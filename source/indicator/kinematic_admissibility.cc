#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/filtered_iterator.h>

#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/indicator/kinematic_admissibility.h>
#include <coulomb_adapt/indicator/narrow_opening.h>
#include <coulomb_adapt/indicator/pointwise_gap.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace coulomb_adapt
{
  namespace
  {
    // Penetration below this is round-off of the displacements.
    double
    negligible_penetration(const std::vector<Tensor<1, 2>> &slave_values,
                           const std::vector<Tensor<1, 2>> &master_values)
    {
      double scale = 0;
      for (const auto *values : {&slave_values, &master_values})
        for (const auto &u : *values)
          scale = std::max(scale, u.norm());
      return 1e-9 * scale;
    }



    // ||sigma(delta)||^2 on every owned cell of the body (N per unit
    // thickness).
    Vector<double>
    cell_energies(const ElasticBody                   &body,
                  const TrilinosWrappers::MPI::Vector &delta)
    {
      struct Scratch
      {
        explicit Scratch(const ElasticBody &body)
          : fe_values(body.mapping(),
                      body.dof_handler().get_fe(),
                      body.cell_quadrature(),
                      update_gradients | update_JxW_values)
          , strains(body.cell_quadrature().size())
        {}
        Scratch(const Scratch &other)
          : fe_values(other.fe_values.get_mapping(),
                      other.fe_values.get_fe(),
                      other.fe_values.get_quadrature(),
                      other.fe_values.get_update_flags())
          , strains(other.strains.size())
        {}
        FEValues<2>                        fe_values;
        std::vector<SymmetricTensor<2, 2>> strains;
      };
      struct Copy
      {
        unsigned int index  = 0;
        double       energy = 0;
      };
      Vector<double> energies(body.triangulation().n_active_cells());
      const FEValuesExtractors::Vector u(0);
      using OwnedCell = FilteredIterator<DoFHandler<2>::active_cell_iterator>;
      const DoFHandler<2> &dofs = body.dof_handler();
      WorkStream::run(
        OwnedCell(IteratorFilters::LocallyOwnedCell(), dofs.begin_active()),
        OwnedCell(IteratorFilters::LocallyOwnedCell(), dofs.end()),
        [&](const OwnedCell &cell, Scratch &scratch, Copy &copy) {
          copy.index  = cell->active_cell_index();
          copy.energy = 0;
          scratch.fe_values.reinit(cell);
          scratch.fe_values[u].get_function_symmetric_gradients(
            delta, scratch.strains);
          for (const unsigned int q :
               scratch.fe_values.quadrature_point_indices())
            {
              const SymmetricTensor<2, 2> stress =
                body.material().stress(scratch.strains[q]);
              copy.energy +=
                stress * scratch.strains[q] * scratch.fe_values.JxW(q);
            }
        },
        [&](const Copy &copy) { energies(copy.index) = copy.energy; },
        Scratch(body),
        Copy());
      return energies;
    }



    // The outward unit normal of the master body at each master node: the
    // mean of its segments' normals.
    std::vector<Tensor<1, 2>>
    master_nodal_normals(const MortarInterface &mortar)
    {
      std::vector<Tensor<1, 2>> normals(mortar.master_nodes().size());
      for (const auto &segment : mortar.master_segment_list())
        for (const unsigned int l : segment.nodes)
          normals[l] += segment.normal;
      for (auto &n : normals)
        if (n.norm() > 0)
          n /= n.norm();
      return normals;
    }



    // What opening each node of @p nodes by 1 along @p normals costs in
    // energy: n . K_jj n from the body's stiffness matrix, or infinity for
    // a node that cannot move on its own (a DoF constrained: a support, a
    // hanging node, a held line). Gathered from the ranks that own the
    // rows, so that every rank opens the same nodes.
    std::vector<double>
    opening_stiffness(const std::vector<MortarInterface::Node> &nodes,
                      const std::vector<Tensor<1, 2>>          &normals,
                      const ElasticBody                        &body)
    {
      const IndexSet     &owned = body.locally_owned_dof_set();
      const auto         &K     = body.system_matrix();
      std::vector<double> packed;
      for (unsigned int n = 0; n < nodes.size(); ++n)
        if (owned.is_element(nodes[n].dofs[0]))
          {
            const auto &dofs = nodes[n].dofs;
            double      k    = std::numeric_limits<double>::infinity();
            if (!body.constraints().is_constrained(dofs[0]) &&
                !body.constraints().is_constrained(dofs[1]))
              {
                k = 0;
                for (unsigned int c = 0; c < 2; ++c)
                  for (unsigned int d = 0; d < 2; ++d)
                    k += normals[n][c] * K.el(dofs[c], dofs[d]) * normals[n][d];
              }
            packed.insert(packed.end(), {double(n), k});
          }
      std::vector<double> stiffness(nodes.size(),
                                    std::numeric_limits<double>::infinity());
      for (const auto &v :
           Utilities::MPI::all_gather(body.triangulation().get_communicator(),
                                      packed))
        for (std::size_t i = 0; i < v.size(); i += 2)
          stiffness[static_cast<unsigned int>(v[i])] = v[i + 1];
      return stiffness;
    }



    // S_b = int sigma(U_c) : eps(delta) - l(delta) for a conforming delta
    // that vanishes on the supports: delta . (K U_c - f) over the DoFs
    // without constraints. K and f are the condensed system (K's columns
    // of constrained DoFs are zero, f has the inhomogeneities' lift
    // -K g subtracted), so on those DoFs K U_c - f = C^T (K_full U_c -
    // f_full), whose product with delta = C delta_free is the integral.
    // (delta . f alone would count the lift's work on delta whenever a
    // support prescribes a nonzero displacement.)
    double
    opening_work(const ElasticBody                   &body,
                 const TrilinosWrappers::MPI::Vector &judged,
                 const TrilinosWrappers::MPI::Vector &delta)
    {
      const MPI_Comm  comm  = body.triangulation().get_communicator();
      const IndexSet &owned = body.locally_owned_dof_set();
      TrilinosWrappers::MPI::Vector residual(owned, comm);
      body.system_matrix().vmult(residual, judged);
      residual -= body.system_rhs();
      double work = 0;
      for (const auto i : owned)
        if (!body.constraints().is_constrained(i))
          work += delta(i) * residual(i);
      return Utilities::MPI::sum(work, comm);
    }



    // The opening's least-energy extension into the body: @p delta keeps
    // its values at the interface @p nodes marked in @p facing (the gaps
    // see only those) and at the constrained DoFs, and minimises
    // ||sigma(delta)|| over the others, K_FF delta_F = -K_FI delta_I. Any
    // conforming extension gives a bound (b and S are computed from the one
    // used), so an iterative solve that does not converge leaves the opening's
    // hat functions (delta_F = 0), which the bound had before this extension:
    // their b was 1.4 to 1.5 times larger (4.40 against 3.18 %, 2.39 against
    // 1.61 %, doc/indicator.md section 4c). S hardly changes: U_c is in
    // equilibrium at the free DoFs.
    void
    extend_opening_into_body(const ElasticBody                        &body,
                             const std::vector<MortarInterface::Node> &nodes,
                             const std::vector<bool>                  &facing,
                             const parameters::LinearSolver &solver_parameters,
                             TrilinosWrappers::MPI::Vector  &delta)
    {
      const MPI_Comm  comm  = body.triangulation().get_communicator();
      const IndexSet &owned = body.locally_owned_dof_set();
      const auto     &K     = body.system_matrix();
      std::vector<types::global_dof_index> fixed;
      for (unsigned int j = 0; j < nodes.size(); ++j)
        if (facing[j])
          for (const auto dof : nodes[j].dofs)
            if (owned.is_element(dof))
              fixed.push_back(dof);
      for (const auto i : owned)
        if (body.constraints().is_constrained(i))
          fixed.push_back(i);
      // The fixed rows keep the size of K's diagonal, which AMG's smoother
      // expects (as contact_correction.cc pins rigid modes).
      double diagonal = 0;
      for (const auto i : fixed)
        diagonal = std::max(diagonal, K.diag_element(i));
      diagonal = Utilities::MPI::max(diagonal, comm);

      TrilinosWrappers::MPI::Vector load(owned, comm);
      K.vmult(load, delta);
      load *= -1;
      for (const auto i : fixed)
        load(i) = 0;
      load.compress(VectorOperation::insert);
      if (Utilities::MPI::max(load.linfty_norm(), comm) == 0)
        return;
      TrilinosWrappers::SparseMatrix matrix;
      matrix.copy_from(K);
      matrix.clear_rows(fixed, diagonal);
      TrilinosWrappers::MPI::Vector interior(owned, comm);
      try
        {
          // Not symmetric: the fixed rows are cleared, their columns not.
          solve_linear_system(matrix,
                              interior,
                              load,
                              body.rigid_body_modes(),
                              solver_parameters,
                              false);
        }
      catch (const SolverControl::NoConvergence &)
        {
          return;
        }
      // An iterative solve leaves the fixed rows only about 0: the
      // interface nodes must keep the opening the gaps were lifted with.
      for (const auto i : fixed)
        interior(i) = 0;
      interior.compress(VectorOperation::insert);
      delta += interior;
    }



    // What opening one node further costs: the gap's rise at the point
    // per unit of its opening, its stiffness K_ii in the normal direction,
    // the pressure's work per unit of its opening P_i, and how far it is
    // already open.
    struct OpeningCost
    {
      double rise;
      double stiffness;
      double pressure_work;
      double opened;
    };



    // The further openings Delta_i >= 0 of the nodes @p costs that lift
    // the gap at one point by @p depth (sum_i rise_i Delta_i = depth) at
    // least cost, sum_i K_i (a_i + Delta_i)^2 + 2 P_i Delta_i (a_i: the
    // opening so far). Sharing the lift among the nodes beats the single
    // cheapest node: a point midway between two master nodes needs twice
    // its depth from either (4 times the energy), half from both. The
    // optimality condition K_i (a_i + Delta_i) + P_i = lambda rise_i / 2
    // for the nodes that open gives Delta_i(lambda), piecewise linear and
    // increasing in lambda: the nodes join in the order of their
    // thresholds t_i = 2 (P_i + K_i a_i) / rise_i.
    std::vector<double>
    least_cost_openings(const std::vector<OpeningCost> &costs,
                        const double                    depth)
    {
      const unsigned int        n = costs.size();
      std::vector<double>       threshold(n);
      std::vector<unsigned int> order(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          threshold[i] =
            2 *
            (costs[i].pressure_work + costs[i].stiffness * costs[i].opened) /
            costs[i].rise;
          order[i] = i;
        }
      std::sort(order.begin(), order.end(), [&](const auto i, const auto j) {
        return threshold[i] < threshold[j];
      });
      // With the first k nodes of the order open: sum_i rise_i Delta_i =
      // lambda sum rise_i^2 / (2 K_i) - sum rise_i (P_i + K_i a_i) / K_i.
      double lambda = 0, slope = 0, offset = 0;
      for (unsigned int k = 0; k < n; ++k)
        {
          const OpeningCost &c = costs[order[k]];
          slope += c.rise * c.rise / (2 * c.stiffness);
          offset +=
            c.rise * (c.pressure_work + c.stiffness * c.opened) / c.stiffness;
          lambda = (depth + offset) / slope;
          if (k + 1 == n || lambda <= threshold[order[k + 1]])
            break;
        }
      std::vector<double> amounts(n, 0.);
      for (unsigned int i = 0; i < n; ++i)
        amounts[i] = std::max(0.,
                              (lambda * costs[i].rise -
                               2 * (costs[i].pressure_work +
                                    costs[i].stiffness * costs[i].opened)) /
                                (2 * costs[i].stiffness));
      return amounts;
    }



    // A node that can open one overlap point: its side, index, and how much
    // the gap there rises per unit of its opening.
    struct Candidate
    {
      unsigned int side;
      unsigned int node;
      double       rise;
    };
  } // namespace



  KinematicAdmissibility
  make_kinematically_admissible(
    const MortarInterface                                      &mortar,
    const std::array<const ElasticBody *, 2>                   &bodies,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements,
    const std::vector<double>                                  &pressure,
    const parameters::LinearSolver &solver_parameters,
    const double                    hypercircle_squared,
    const bool                      open)
  {
    KinematicAdmissibility                                          measured;
    const std::array<const std::vector<MortarInterface::Node> *, 2> nodes = {
      {&mortar.slave_nodes(), &mortar.master_nodes()}};
    std::vector<MortarInterface::OverlapPoint> points =
      mortar.overlap_quadrature(gap_sample_rule(mortar.slave_element_degree()));
    std::array<std::vector<Tensor<1, 2>>, 2> values;
    for (unsigned int s = 0; s < 2; ++s)
      values[s] =
        MortarInterface::gather_nodal_displacements(*nodes[s],
                                                    *displacements[s]);
    // The samples are the opening's points, and so are the gap's minima
    // between them (interior_gap_minima()): one that penetrates is lifted
    // like they are.
    const auto minima = interior_gap_minima(mortar, values[0], values[1]);
    points.insert(points.end(), minima.begin(), minima.end());
    const double negligible = negligible_penetration(values[0], values[1]);
    std::vector<double> gaps =
      pointwise_gaps(mortar, points, values[0], values[1]);
    for (unsigned int q = 0; q < points.size(); ++q)
      if (-gaps[q] > std::max(negligible, measured.penetration))
        {
          measured.penetration = -gaps[q];
          measured.where       = points[q].slave_point;
        }
    if (measured.penetration == 0 || !open)
      return measured;

    // The nodal opening, after the narrow one of @p narrow (if any) has
    // lifted the gaps by its rise.
    const std::vector<MortarInterface::OverlapPoint> measured_points = points;
    const std::vector<double>                        measured_gaps   = gaps;
    const std::array<std::vector<Tensor<1, 2>>, 2>   measured_values = values;
    const auto open_nodes = [&](const NarrowOpening *narrow) {
      KinematicAdmissibility                     result = measured;
      std::vector<MortarInterface::OverlapPoint> points = measured_points;
      std::vector<double>                        gaps   = measured_gaps;
      std::array<std::vector<Tensor<1, 2>>, 2>   values = measured_values;
      result.opening_applied                            = true;
      if (narrow != nullptr)
        {
          const auto kinks = narrow->kinks(mortar);
          const auto kink_gaps =
            pointwise_gaps(mortar, kinks, values[0], values[1]);
          points.insert(points.end(), kinks.begin(), kinks.end());
          gaps.insert(gaps.end(), kink_gaps.begin(), kink_gaps.end());
          for (unsigned int q = 0; q < points.size(); ++q)
            gaps[q] += narrow->rise(mortar, points[q]);
          result.narrow = narrow->patch;
        }

      // Each node moves into its own body: the slave node against its
      // normal, the master node against the master's normal. Opening node i
      // by delta costs about K_ii delta^2 in energy and 2 P_i delta in the
      // contact term (P_i = int p^ times the gap's rise per unit opening of
      // i); least_cost_openings() shares each lift among the nodes by that
      // cost.
      const std::array<std::vector<Tensor<1, 2>>, 2> normals = {
        {[&] {
           std::vector<Tensor<1, 2>> n;
           for (const auto &node : mortar.slave_nodes())
             n.push_back(node.normal);
           return n;
         }(),
         master_nodal_normals(mortar)}};
      std::array<std::vector<double>, 2> stiffness;
      for (unsigned int s = 0; s < 2; ++s)
        stiffness[s] = opening_stiffness(*nodes[s], normals[s], *bodies[s]);
      // The nodes that lift each point, and the points each node lifts.
      std::vector<std::vector<Candidate>> lifters;
      // Per node: (point, rise) of every point it lifts.
      using LiftedPoints =
        std::vector<std::vector<std::pair<unsigned int, double>>>;
      std::array<LiftedPoints, 2> lifted = {
        {LiftedPoints(nodes[0]->size()), LiftedPoints(nodes[1]->size())}};
      const auto add_lifters = [&](const unsigned int q) {
        const auto &overlap = mortar.overlaps()[points[q].overlap];
        const auto &s_seg = mortar.slave_segment_list()[overlap.slave_segment];
        const auto &m_seg =
          mortar.master_segment_list()[overlap.master_segment];
        const auto         phi_s = mortar.slave_shape_values(points[q].xi);
        const auto         phi_m = mortar.master_shape_values(points[q].eta);
        const Tensor<1, 2> n     = gap_normal(mortar, points[q]);
        Assert(q == lifters.size(), ExcInternalError());
        lifters.emplace_back();
        for (unsigned int k = 0; k < s_seg.nodes.size(); ++k)
          lifters[q].push_back(
            {0, s_seg.nodes[k], phi_s[k] * (normals[0][s_seg.nodes[k]] * n)});
        for (unsigned int k = 0; k < m_seg.nodes.size(); ++k)
          lifters[q].push_back(
            {1, m_seg.nodes[k], -phi_m[k] * (normals[1][m_seg.nodes[k]] * n)});
        for (const auto &c : lifters[q])
          lifted[c.side][c.node].emplace_back(q, c.rise);
      };
      for (unsigned int q = 0; q < points.size(); ++q)
        add_lifters(q);

      // Worst penetration first, each by its cheapest openings of the nodes
      // that can lift it; the gaps move linearly with the openings, so they
      // are updated exactly (but for hanging interface nodes, which follow
      // their masters when the constraints are distributed: the gaps of u^
      // are measured again below).
      std::array<std::vector<double>, 2> opening = {
        {std::vector<double>(nodes[0]->size(), 0.),
         std::vector<double>(nodes[1]->size(), 0.)}};
      std::array<std::vector<double>, 2> pressure_work = opening;
      {
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const double p =
              slave_bernstein_interpolant(mortar, points[q], pressure);
            for (const auto &c : lifters[q])
              if (c.rise > 0)
                pressure_work[c.side][c.node] +=
                  std::max(p, 0.) * c.rise * points[q].weight;
          }
      }
      // A point no free node can open stays penetrating (penetration_after
      // says so); the others are still opened.
      std::vector<bool> unopenable(points.size(), false);
      const auto        open_worst_first = [&]() {
        for (unsigned int step = 0; step < 4 * points.size(); ++step)
          {
            unsigned int worst = points.size();
            double       depth = negligible;
            for (unsigned int q = 0; q < points.size(); ++q)
              if (!unopenable[q] && -gaps[q] > depth)
                {
                  depth = -gaps[q];
                  worst = q;
                }
            if (worst == points.size())
              break;
            std::vector<Candidate> usable;
            for (const auto &c : lifters[worst])
              if (c.rise > 1e-3 && std::isfinite(stiffness[c.side][c.node]) &&
                  stiffness[c.side][c.node] > 0)
                usable.push_back(c);
            if (usable.empty())
              {
                unopenable[worst] = true;
                continue;
              }
            std::vector<OpeningCost> costs;
            for (const auto &c : usable)
              costs.push_back({c.rise,
                               stiffness[c.side][c.node],
                               pressure_work[c.side][c.node],
                               opening[c.side][c.node]});
            const std::vector<double> amounts =
              least_cost_openings(costs, depth);
            for (unsigned int k = 0; k < usable.size(); ++k)
              if (amounts[k] > 0)
                {
                  opening[usable[k].side][usable[k].node] += amounts[k];
                  for (const auto &[q, rise] :
                       lifted[usable[k].side][usable[k].node])
                    gaps[q] += amounts[k] * rise;
                }
          }
      };
      open_worst_first();
      // Opening moves the gaps' minima between the samples: a minimum of the
      // opened gaps that penetrates becomes a point of its own and is lifted
      // in turn. On blocks with the centre line held the first opening left
      // 1.2e-8 mm (P2 triangles) and 2.9e-8 mm (Q2) at such minima, hertz P2
      // (curved) 2.1e-9 mm; the rounds after it left 1.8e-10 and 3e-13 mm,
      // 1e-12 mm and 4.5e-11 mm.
      for (unsigned int round = 0;
           round < 8 && mortar.slave_element_degree() >= 2;
           ++round)
        {
          std::array<std::vector<Tensor<1, 2>>, 2> opened = values;
          for (unsigned int s = 0; s < 2; ++s)
            for (unsigned int j = 0; j < nodes[s]->size(); ++j)
              opened[s][j] -= opening[s][j] * normals[s][j];
          const auto vertices =
            interior_gap_minima(mortar, opened[0], opened[1]);
          const std::vector<double> vertex_gaps =
            pointwise_gaps(mortar, vertices, opened[0], opened[1]);
          bool penetrating = false;
          for (unsigned int k = 0; k < vertices.size(); ++k)
            if (-vertex_gaps[k] > negligible)
              {
                points.push_back(vertices[k]);
                gaps.push_back(vertex_gaps[k]);
                unopenable.push_back(false);
                add_lifters(points.size() - 1);
                penetrating = true;
              }
          if (!penetrating)
            break;
          open_worst_first();
        }

      // The extension keeps the interface nodes whose segments face the
      // other side (the gaps see those only: every sample point, and the
      // contact term, lies on an overlap); the others, beyond the ends of the
      // other side, move freely. Kept at 0 they pinned the opening of the
      // last facing node: on the remeshed punch (cycle 1) b was 2.008 % of
      // D instead of 1.785 %. (Freeing the tangential components of the
      // facing nodes of straight segments too gave 1.719 %; the facing nodes
      // that are not opened, 1.593 %, but the contact term of their opening
      // under the pressure raised the estimate: 7.871 % instead of 7.347 %.)
      // Like U_c itself, the free nodes are not checked against the other
      // body where no segments are paired: penetration_after looks at the
      // overlaps only.
      std::array<std::vector<bool>, 2> facing = {
        {std::vector<bool>(nodes[0]->size(), false),
         std::vector<bool>(nodes[1]->size(), false)}};
      for (const auto &overlap : mortar.overlaps())
        {
          for (const unsigned int j :
               mortar.slave_segment_list()[overlap.slave_segment].nodes)
            facing[0][j] = true;
          for (const unsigned int j :
               mortar.master_segment_list()[overlap.master_segment].nodes)
            facing[1][j] = true;
        }

      // u^ = U_c + delta, delta given at the opened nodes and extended into
      // the body; the bodies' constraints then hold for u^ as for U_c.
      for (unsigned int s = 0; s < 2; ++s)
        {
          const ElasticBody &body  = *bodies[s];
          const MPI_Comm     comm  = body.triangulation().get_communicator();
          const IndexSet    &owned = body.locally_owned_dof_set();
          TrilinosWrappers::MPI::Vector opening_at_nodes(owned, comm);
          for (unsigned int j = 0; j < nodes[s]->size(); ++j)
            if (opening[s][j] > 0)
              {
                ++result.n_opened_nodes[s];
                const Tensor<1, 2> move = -opening[s][j] * normals[s][j];
                for (unsigned int c = 0; c < 2; ++c)
                  if (const auto dof = (*nodes[s])[j].dofs[c];
                      owned.is_element(dof))
                    opening_at_nodes(dof) = move[c];
              }
          opening_at_nodes.compress(VectorOperation::insert);
          // Where the penetration is round-off of the solves (5.6e-11 mm on
          // press_fit_torque, 244 + 244 nodes), the hat functions' b is as
          // negligible, and the extension's solve would be most of the
          // estimator's cost.
          if (result.n_opened_nodes[s] > 0 &&
              result.penetration > 1e3 * negligible)
            extend_opening_into_body(
              body, *nodes[s], facing[s], solver_parameters, opening_at_nodes);
          // U_c without its ghost entries: u^ and delta have none.
          TrilinosWrappers::MPI::Vector judged(owned, comm);
          judged = *displacements[s];
          TrilinosWrappers::MPI::Vector opened(judged);
          opened += opening_at_nodes;
          body.constraints().distribute(opened);
          TrilinosWrappers::MPI::Vector opened_ghosted;
          opened_ghosted.reinit(body.locally_owned_dof_set(),
                                body.locally_relevant_dof_set(),
                                comm);
          opened_ghosted = opened;
          TrilinosWrappers::MPI::Vector delta(opened);
          delta -= judged;
          TrilinosWrappers::MPI::Vector delta_ghosted(
            body.locally_owned_dof_set(),
            body.locally_relevant_dof_set(),
            comm);
          delta_ghosted             = delta;
          result.opening_squared[s] = cell_energies(body, delta_ghosted);
          const double nodal_squared =
            Utilities::MPI::sum(result.opening_squared[s].l1_norm(), comm);
          result.opening_work += opening_work(body, judged, delta);
          if (narrow != nullptr && narrow->patch.side == s)
            {
              // ||sigma(delta_nodal + delta_narrow)|| <= b_n + b_f, split
              // into the cells as (b_n + b_f)^2 = (1 + g) b_n^2 + (1 + 1/g)
              // b_f^2 with g = b_f / b_n.
              const double b_n = std::sqrt(nodal_squared);
              const double b_f = std::sqrt(narrow->norm_squared);
              if (b_n > 0 && b_f > 0)
                {
                  result.opening_squared[s] *= 1 + b_f / b_n;
                  result.opening_squared[s].add(1 + b_n / b_f, narrow->energy);
                }
              else if (b_f > 0)
                result.opening_squared[s] = narrow->energy;
              result.opening_norm_squared += (b_n + b_f) * (b_n + b_f);
              result.opening_work += narrow->work;
            }
          else
            result.opening_norm_squared += nodal_squared;
          values[s] =
            MortarInterface::gather_nodal_displacements(*nodes[s],
                                                        opened_ghosted);
        }

      // The opening moves the minima between the samples: u^'s own are
      // measured.
      const auto opened_minima =
        interior_gap_minima(mortar, values[0], values[1]);
      points.insert(points.end(), opened_minima.begin(), opened_minima.end());
      {
        const std::vector<double> after =
          pointwise_gaps(mortar, points, values[0], values[1]);
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const double g =
              after[q] +
              (narrow != nullptr ? narrow->rise(mortar, points[q]) : 0.);
            if (-g > negligible)
              result.penetration_after = std::max(result.penetration_after, -g);
          }
      }
      return result;
    };

    // The nodal opening alone, and with the narrow opening of one side
    // under the deepest penetrations: the one with the smaller bound
    // b + sqrt(C + b^2 + 2 S) is kept (either is a bound).
    KinematicAdmissibility best  = open_nodes(nullptr);
    const auto             bound = [&](const double b2, const double work) {
      return std::sqrt(b2) + std::sqrt(std::max(0.,
                                                hypercircle_squared + b2 +
                                                  2 * std::max(work, -b2 / 2)));
    };
    const double nodal_bound =
      bound(best.opening_norm_squared, best.opening_work);
    // The narrow opening can at most take back what the opening adds to
    // sqrt(C); where that is below 10 % of sqrt(C) (the deep meshes of an
    // adaptive run: on the punch's 228,372 DoFs 6 %, for a gain of 2.5 %)
    // it is not worth its patches' solves and a second nodal opening (4
    // times this section's time there).
    if (measured.penetration > 1e3 * negligible &&
        nodal_bound > 1.1 * std::sqrt(hypercircle_squared))
      {
        // The side whose own b_f and S_f promise the smaller bound, chosen
        // on patches bisected twice (a sixteenth of the fine cells; on the
        // cre-driven blocks' 874-DoF mesh the two full patches took 0.13 s
        // against 0.04 s for the rest of the estimate); its patch is then
        // bisected fully, and the nodal opening (a solve per body) run
        // after it.
        const double                 threshold = 1e-2 * measured.penetration;
        std::optional<NarrowOpening> coarse;
        for (unsigned int s = 0; s < 2; ++s)
          if (auto narrow = make_narrow_opening(
                mortar, bodies, displacements, s, threshold, 2))
            if (!coarse || bound(narrow->norm_squared, narrow->work) <
                             bound(coarse->norm_squared, coarse->work))
              coarse = std::move(narrow);
        std::optional<NarrowOpening> chosen;
        if (coarse)
          chosen = coarse->patch.refinements < 2 ?
                     std::move(coarse) :
                     make_narrow_opening(mortar,
                                         bodies,
                                         displacements,
                                         coarse->patch.side,
                                         threshold);
        if (chosen)
          {
            KinematicAdmissibility candidate = open_nodes(&*chosen);
            if (candidate.penetration_after <= best.penetration_after &&
                bound(candidate.opening_norm_squared, candidate.opening_work) <
                  nodal_bound)
              best = std::move(candidate);
          }
      }
    return best;
  }



} // namespace coulomb_adapt
