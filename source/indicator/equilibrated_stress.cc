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
#include <coulomb_adapt/indicator/equilibration_mesh.h>
#include <coulomb_adapt/indicator/equilibration_node_systems.h>
#include <coulomb_adapt/indicator/held_reactions.h>
#include <coulomb_adapt/indicator/local_neumann_problem.h>
#include <coulomb_adapt/indicator/local_problem_loads.h>
#include <coulomb_adapt/indicator/traction_optimisation.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

namespace coulomb_adapt
{
  using namespace equilibration;

  namespace
  {
    // The element equilibration needs every face to be a whole face of
    // both its cells. Checked on the owned cells, whose neighbours are all
    // owned or ghosts: a ghost cell's neighbour may be an artificial cell
    // of a coarser level (parallel::fullydistributed keeps no more of the
    // mesh than the ghost layer needs), which looked like a hanging node
    // on 2 ranks. A hanging face has an owned cell on one side, so every
    // one is found by some rank; the verdict is collective, so that no
    // rank waits for one that has stopped.
    void
    check_conforming(const ElasticBody &body)
    {
      bool conforming = true;
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            conforming = conforming && (cell->at_boundary(f) ||
                                        (!cell->face(f)->has_children() &&
                                         !cell->neighbor_is_coarser(f)));
      conforming =
        Utilities::MPI::min(static_cast<unsigned int>(conforming),
                            body.triangulation().get_communicator()) == 1;
      AssertThrow(conforming,
                  ExcMessage("Error indicator/Estimator = cre: the mesh of " +
                             body.name() +
                             " has hanging nodes. The element equilibration "
                             "is written for conforming meshes: use "
                             "Adaptation/Strategy = remesh or uniform "
                             "(quadrilaterals without a scene's local "
                             "refinement, or triangles)."));
    }



    // Step 1: the local cells (owned and ghost) and their element residuals
    // int_E sigma(u) : eps(phi) - f . phi; slot_of maps a cell to its
    // place in the result.
    std::vector<CellData>
    collect_cells(const ElasticBody                   &body,
                  const TrilinosWrappers::MPI::Vector &u,
                  std::map<CellId, unsigned int>      &slot_of)
    {
      const auto                      &dof_handler = body.dof_handler();
      const FiniteElement<2>          &fe          = dof_handler.get_fe();
      const FiniteElement<2>          &base        = fe.base_element(0);
      const unsigned int               n_nodes     = base.n_dofs_per_cell();
      const ElasticMaterial           &material    = body.material();
      const BodyDescription           &description = body.description();
      const FEValuesExtractors::Vector displacement(0);
      std::vector<CellData>            cells;
      FEValues<2>                      fe_values(body.mapping(),
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
      return cells;
    }



    // Step 2: the faces of the local cells: geometry, orientation (the
    // plus cell is the one with the smaller CellId), their nodes, and which
    // moments are unknown (interior and Dirichlet edges).
    std::vector<FaceData>
    collect_faces(const ElasticBody &body, std::vector<CellData> &cells)
    {
      const unsigned int n_nodes =
        body.dof_handler().get_fe().base_element(0).n_dofs_per_cell();
      const BodyDescription &description = body.description();
      std::map<types::boundary_id, ComponentMask> dirichlet_on;
      for (const auto &d : description.dirichlet)
        dirichlet_on[d.boundary_id] = d.components;
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
                  const auto d =
                    dirichlet_on.find(cell->face(f)->boundary_id());
                  for (unsigned int c = 0; c < 2; ++c)
                    face.unknown[c] = (d != dirichlet_on.end() && d->second[c]);
                }
              face.nodes.clear();
              face.s.clear();
              face.points.clear();
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
                  if (s > -1e-8 && s < 1 + 1e-8 &&
                      distance < 0.05 * face.length)
                    {
                      face.nodes.push_back(cells[slot].nodes[k]);
                      face.node_dofs.push_back(cells[slot].component_dofs[k]);
                      // Vertices at 0 and 1, an edge's middle node at 1/2.
                      face.s.push_back(std::round(2 * s) / 2);
                      face.points.push_back(x);
                    }
                }
            }
        }

      return faces;
    }



    // Step 2, continued: the moments known on loaded edges. The prescribed
    // traction uses the FE assembly's face quadrature, so that the moments
    // are those of the FE load vector. Also sizes every face's moments.
    void
    set_prescribed_moments(const ElasticBody           &body,
                           const std::vector<CellData> &cells,
                           std::vector<FaceData>       &faces)
    {
      const unsigned int p = body.dof_handler().get_fe().base_element(0).degree;
      std::map<types::boundary_id, const TractionFunction *> traction_on;
      for (const auto &t : body.description().tractions)
        traction_on[t.boundary_id] = &t.traction;
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
                const double            s   = face_gauss.point(q)[0];
                const FacePointGeometry g   = face_geometry(face, s);
                const Tensor<1, 2>      F   = (*t->second)(g.point, g.normal);
                const auto              phi = face_shape_values(face.s, s);
                for (unsigned int k = 0; k < face.nodes.size(); ++k)
                  for (unsigned int c = 0; c < 2; ++c)
                    face.moments[k][c] +=
                      F[c] * phi[k] * face_gauss.weight(q) * g.length_element;
              }
        }
    }



    // ... and on contact edges, from the corrected contact traction.
    void
    add_contact_moments(const std::vector<CellData>          &cells,
                        const std::map<CellId, unsigned int> &slot_of,
                        const ContactTractionData            &contact,
                        std::vector<FaceData>                &faces)
    {
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
    }



    // The moments of the averaged FE traction 1/2 (sigma_c|E+ +
    // sigma_c|E-) n+ (the one side's on Dirichlet edges), from each side's
    // own face quadrature: what the node systems stay closest to.
    void
    set_averaged_moments(const ElasticBody                   &body,
                         const TrilinosWrappers::MPI::Vector &u,
                         const std::vector<CellData>         &cells,
                         std::vector<FaceData>               &faces)
    {
      const FiniteElement<2>            &fe       = body.dof_handler().get_fe();
      const unsigned int                 p        = fe.base_element(0).degree;
      const ElasticMaterial             &material = body.material();
      const FEValuesExtractors::Vector   displacement(0);
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



    // The nodal coefficients of the polynomial of degree p on @p face
    // with @p moments (the inverse edge mass matrix on the chord).
    std::vector<std::array<double, 2>>
    coefficients_of(const FaceData                           &face,
                    const std::vector<std::array<double, 2>> &moments)
    {
      const unsigned int                 n = face.nodes.size();
      std::vector<std::array<double, 2>> coefficients(n, {{0., 0.}});
      for (unsigned int k = 0; k < n; ++k)
        for (unsigned int l = 0; l < n; ++l)
          for (unsigned int c = 0; c < 2; ++c)
            coefficients[k][c] += face.mass_inverse(k, l) * moments[l][c];
      return coefficients;
    }



    // F on a face: the polynomial with the face's moments.
    void
    update_coefficients(FaceData &face)
    {
      if (face.plus < 0 || (!face.unknown[0] && !face.unknown[1]))
        face.coefficients.assign(face.nodes.size(), {{0., 0.}});
      else
        face.coefficients = coefficients_of(face, face.moments);
    }



    // Step 4: each face's inverse edge mass matrix and F.
    void
    set_edge_polynomials(const unsigned int p, std::vector<FaceData> &faces)
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
          if (!face.held_moments.empty())
            face.held_coefficients = coefficients_of(face, face.held_moments);
        }
    }



    // Step 6 without the optimisation (which gives the errors from each
    // cell's quadratic form): the local Neumann problems and the errors,
    // cell by cell.
    void
    classical_errors(const ElasticBody                   &body,
                     const std::vector<CellData>         &cells,
                     LocalNeumannProblem                 &local,
                     const LocalProblemLoads             &loads,
                     const TrilinosWrappers::MPI::Vector &u_kinematic,
                     EquilibratedStressErrors            &result)
    {
      result.error_squared.reinit(body.triangulation().n_active_cells());
      double         sum_norm = 0;
      Vector<double> load(local.n_coefficients()), coefficients;
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        if (cells[slot].owned)
          {
            local.reinit(cells[slot].cell, u_kinematic);
            loads.cell_load(local, slot, load);
            result.local_problem_defect =
              std::max(result.local_problem_defect,
                       local.solve(load, coefficients));
            const auto errors = local.errors(coefficients);
            result.error_squared(cells[slot].cell->active_cell_index()) =
              errors[0];
            sum_norm += errors[1];
          }
      const MPI_Comm comm     = body.triangulation().get_communicator();
      result.sum_norm_squared = Utilities::MPI::sum(sum_norm, comm);
      result.error_squared_before_optimisation =
        Utilities::MPI::sum(result.error_squared.l1_norm(), comm);
    }



    // @p v with the ghost entries of @p body's locally relevant DoFs.
    TrilinosWrappers::MPI::Vector
    ghosted_copy(const ElasticBody                   &body,
                 const TrilinosWrappers::MPI::Vector &v)
    {
      TrilinosWrappers::MPI::Vector ghosted(
        body.locally_owned_dof_set(),
        body.locally_relevant_dof_set(),
        body.triangulation().get_communicator());
      ghosted = v;
      return ghosted;
    }
  } // namespace



  EquilibratedStressErrors
  equilibrated_stress_errors(
    const ElasticBody                   &body,
    const TrilinosWrappers::MPI::Vector &u_equilibrium,
    const TrilinosWrappers::MPI::Vector &u_kinematic_in,
    const ContactTractionData           &contact,
    const unsigned int                   degree_increase,
    const bool                           optimise_tractions,
    const bool                           relax_equilibration,
    const CreMinimisation               &minimisation,
    TimerOutput                         *timer)
  {
    // Ghosted copies: the node systems read the ghost cells too, and a
    // caller's vector may hold the owned entries only (the corrected
    // solutions did until 2026-11-30; CorrectedContactSolution's now
    // carry them, so for the program this copy is a plain copy).
    const MPI_Comm comm = body.triangulation().get_communicator();
    const TrilinosWrappers::MPI::Vector u = ghosted_copy(body, u_equilibrium);
    const TrilinosWrappers::MPI::Vector u_kinematic =
      ghosted_copy(body, u_kinematic_in);
    const FiniteElement<2> &base = body.dof_handler().get_fe().base_element(0);
    const unsigned int      p    = base.degree;

    // 1.-2. The local mesh, the known moments and the averaged ones.
    check_conforming(body);
    std::map<CellId, unsigned int> slot_of;
    std::vector<CellData>          cells = collect_cells(body, u, slot_of);
    std::vector<FaceData>          faces = collect_faces(body, cells);
    set_prescribed_moments(body, cells, faces);
    add_contact_moments(cells, slot_of, contact, faces);
    EquilibratedStressErrors result;
    result.uncarried_held_reaction = Utilities::MPI::max(
      carry_held_reactions(body.description(), cells, faces), comm);
    set_averaged_moments(body, u, cells, faces);

    // 3. The node systems, for every node of a locally owned cell (its
    // star is then all local: the ghost layer holds every cell that shares
    // a vertex with an owned cell).
    solve_node_systems(cells, faces, base.n_dofs_per_cell(), result);

    // 4. F on each face.
    set_edge_polynomials(p, faces);

    // 5. The free parameters of the node systems (one per interior or
    // Dirichlet node and component) chosen to minimise the estimate
    // sum_E ||sigma^ - sigma_c||^2 itself, instead of the distance to the
    // averaged traction: sigma^ is affine in them, so this is one sparse
    // symmetric positive definite system with the pattern of the
    // stiffness matrix. Any value of the parameters keeps sigma^
    // statically admissible, so an inexact solve only makes the bound
    // less tight. The optimisation also gives the errors (6.).
    LocalNeumannProblem     local(body, p + degree_increase);
    const LocalProblemLoads loads(
      body.description(), cells, faces, contact, p, p + degree_increase);
    // The relaxed modes, like every choice of sigma^, bound the error of
    // a kinematically admissible u_c. Where the displacement data are not
    // interpolated exactly, the minimisation exploits their interpolation
    // error (the manufactured scene: estimates 0.5-3.5 % below the exact
    // error), unless cre_estimate.cc adds its lift (dirichlet_data_lift.h).
    result.relaxed =
      optimise_tractions && relax_equilibration && degree_increase >= 3 &&
      (body.description().displacement_data_interpolated_exactly ||
       minimisation.lift_displacement_data);
    // With the lift, the local problems measure sigma^ - sigma(u_c + r):
    // the minimisation then sees the kinematic side the bound uses.
    std::optional<DirichletDataLiftField> lift;
    if (minimisation.lift_displacement_data)
      {
        lift.emplace(body, u_kinematic);
        if (lift->active())
          local.set_kinematic_lift(&*lift);
      }
    // The estimate at the minimum from local problems of a higher degree
    // (CreMinimisation::evaluation_degree_increase).
    const unsigned int evaluation_degree =
      p + degree_increase + minimisation.evaluation_degree_increase;
    std::optional<LocalNeumannProblem> evaluation_local;
    std::optional<LocalProblemLoads>   evaluation_loads;
    std::optional<LocalProblems>       evaluation;
    if (minimisation.evaluation_degree_increase > 0)
      {
        evaluation_local.emplace(body, evaluation_degree);
        if (lift && lift->active())
          evaluation_local->set_kinematic_lift(&*lift);
        evaluation_loads.emplace(
          body.description(), cells, faces, contact, p, evaluation_degree);
        evaluation.emplace(LocalProblems{*evaluation_local, *evaluation_loads});
      }
    if (optimise_tractions)
      optimise_free_parameters(body,
                               cells,
                               faces,
                               local,
                               u_kinematic,
                               loads,
                               // A bubble of degree p + 1 needs local
                               // problems of degree p + 3 to be resolved:
                               // with p + 2 the minimisation finds the
                               // local problems' blind spots (Q2: an
                               // estimate below the exact error).
                               degree_increase >= 3,
                               result.relaxed,
                               minimisation,
                               result,
                               evaluation ? &*evaluation : nullptr,
                               timer);
    else
      classical_errors(body,
                       cells,
                       evaluation ? *evaluation_local : local,
                       evaluation ? *evaluation_loads : loads,
                       u_kinematic,
                       result);

    result.node_system_defect =
      Utilities::MPI::max(result.node_system_defect, comm);
    result.local_problem_defect =
      Utilities::MPI::max(result.local_problem_defect, comm);
    return result;
  }
} // namespace coulomb_adapt
