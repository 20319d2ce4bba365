#include <deal.II/base/bounding_box.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/grid_tools_cache.h>

#include <deal.II/numerics/rtree.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/indicator/exact_error.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

namespace coulomb_adapt
{
  // The reference solution of a scene without an exact one (theory.md
  // sections 6 and 8): the judged meshes refined again, solved like the program
  // solves them, and its stresses evaluated at the judged meshes' points.

  namespace
  {
    // The active mesh of a triangle body, gathered from all ranks, as a
    // coarse mesh: cells with their material and manifold ids, boundary
    // edges with their boundary and manifold ids (the scene's manifolds
    // are attached again by ElasticBody::replace_mesh). A vertex shared by
    // the cells of several ranks has the same coordinates on each: they
    // come from the same serial mesh.
    CoarseMeshData
    gather_triangle_mesh(const ElasticBody &body)
    {
      // Per cell: material id, manifold id, 3 x (x, y); per boundary
      // edge: a negative marker, boundary id, manifold id, 2 x (x, y).
      std::vector<double> packed;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            AssertThrow(cell->n_vertices() == 3,
                        ExcMessage("gather_triangle_mesh: body '" +
                                   body.name() + "' is not a triangle mesh"));
            packed.push_back(cell->material_id());
            packed.push_back(cell->manifold_id());
            for (const unsigned int v : cell->vertex_indices())
              packed.insert(packed.end(),
                            {cell->vertex(v)[0], cell->vertex(v)[1]});
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary())
                {
                  packed.insert(packed.end(),
                                {-1.,
                                 double(face->boundary_id()),
                                 double(face->manifold_id())});
                  for (unsigned int v = 0; v < 2; ++v)
                    packed.insert(packed.end(),
                                  {face->vertex(v)[0], face->vertex(v)[1]});
                }
          }

      CoarseMeshData                                    mesh;
      std::map<std::pair<double, double>, unsigned int> vertex_number;
      const auto vertex = [&](const double x, const double y) {
        const auto [it, inserted] =
          vertex_number.emplace(std::make_pair(x, y), mesh.vertices.size());
        if (inserted)
          mesh.vertices.emplace_back(x, y);
        return it->second;
      };
      for (const auto &part :
           Utilities::MPI::all_gather(body.triangulation().get_communicator(),
                                      packed))
        for (std::size_t i = 0; i < part.size();)
          if (part[i] >= 0)
            {
              CellData<2> cell(3);
              cell.material_id = static_cast<types::material_id>(part[i]);
              cell.manifold_id = static_cast<types::manifold_id>(part[i + 1]);
              for (unsigned int v = 0; v < 3; ++v)
                cell.vertices[v] =
                  vertex(part[i + 2 + 2 * v], part[i + 3 + 2 * v]);
              mesh.cells.push_back(cell);
              i += 8;
            }
          else
            {
              CellData<1> line;
              line.boundary_id = static_cast<types::boundary_id>(part[i + 1]);
              line.manifold_id = static_cast<types::manifold_id>(part[i + 2]);
              for (unsigned int v = 0; v < 2; ++v)
                line.vertices[v] =
                  vertex(part[i + 3 + 2 * v], part[i + 4 + 2 * v]);
              mesh.boundary_lines.boundary_lines.push_back(line);
              i += 7;
            }
      return mesh;
    }



    // Make @p body's quadrilateral mesh the judged one: refine every cell
    // that is an ancestor of a judged cell, coarsen every cell that is a
    // descendant of one, until the active cells are the judged cells. Both
    // start from the scene's coarse mesh, so a CellId names the same cell
    // in both; p4est keeps the judged mesh's 2:1 balance, which it made.
    void
    replay_refinement(const ElasticBody &judged, ElasticBody &body)
    {
      std::vector<CellId::binary_type> owned;
      for (const auto &cell : judged.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          owned.push_back(cell->id().template to_binary<2>());
      std::set<CellId> active, ancestors;
      for (const auto &part :
           Utilities::MPI::all_gather(judged.triangulation().get_communicator(),
                                      owned))
        for (const auto &binary : part)
          {
            const CellId id(binary);
            active.insert(id);
            const auto children = id.get_child_indices();
            for (unsigned int level = 0; level < children.size(); ++level)
              ancestors.insert(
                CellId(id.get_coarse_cell_id(), level, children.data()));
          }

      const unsigned int max_rounds =
        2 * judged.triangulation().n_global_levels() + 4;
      for (unsigned int round = 0;; ++round)
        {
          std::vector<signed char> decisions(
            body.triangulation().n_active_cells(), 0);
          bool changes = false;
          for (const auto &cell : body.triangulation().active_cell_iterators())
            if (cell->is_locally_owned() && active.count(cell->id()) == 0)
              {
                decisions[cell->active_cell_index()] =
                  ancestors.count(cell->id()) > 0 ? 1 : -1;
                changes = true;
              }
          if (!Utilities::MPI::logical_or(
                changes, body.triangulation().get_communicator()))
            break;
          AssertThrow(round < max_rounds,
                      ExcMessage("make_refined_body: the mesh of body '" +
                                 judged.name() +
                                 "' could not be rebuilt from the scene's "
                                 "coarse mesh by refinement and coarsening"));
          body.refine_and_coarsen(decisions);
        }
    }
  } // namespace



  std::unique_ptr<ElasticBody>
  make_refined_body(const ElasticBody &judged,
                    const Scene       &scene,
                    const unsigned int body_index,
                    const Parameters  &parameters,
                    const unsigned int refinements)
  {
    const MPI_Comm comm = judged.triangulation().get_communicator();
    const CellType cell_type =
      judged.is_simplex_mesh() ? CellType::triangle : CellType::quadrilateral;
    auto body = std::make_unique<ElasticBody>(
      comm, scene, body_index, cell_type, 0, parameters.finite_elements);
    if (judged.is_simplex_mesh())
      body->replace_mesh(gather_triangle_mesh(judged));
    else
      replay_refinement(judged, *body);
    AssertThrow(body->triangulation().n_global_active_cells() ==
                  judged.triangulation().n_global_active_cells(),
                ExcInternalError());
    for (unsigned int r = 0; r < refinements; ++r)
      body->refine_uniformly();
    body->setup_system();
    body->assemble_system();
    return body;
  }



  namespace
  {
    // Both bodies solved: with contact if both have a contact boundary,
    // otherwise each on its own.
    unsigned int
    solve_quietly(std::array<std::unique_ptr<ElasticBody>, 2> &bodies,
                  const Parameters                            &parameters,
                  const ConditionalOStream                    &quiet)
    {
      if (bodies[0]->description().contact_boundary_id ==
            numbers::invalid_boundary_id ||
          bodies[1]->description().contact_boundary_id ==
            numbers::invalid_boundary_id)
        {
          for (auto &body : bodies)
            body->solve(parameters.linear_solver);
          return 0;
        }
      ContactSolver solver(*bodies[0],
                           *bodies[1],
                           parameters.contact,
                           parameters.linear_solver,
                           quiet);
      return solver.solve().newton_iterations;
    }
  } // namespace



  namespace
  {
    using Gradient = Tensor<1, 2, Tensor<1, 2>>;

    // The displacement gradient at those of @p points that lie in a
    // locally owned cell of @p body (none for the others). The candidate
    // cells come from the tree of the owned cells' bounding boxes; a
    // point belongs to a cell whose own reference cell contains its unit
    // point. deal.II 9.4's RemotePointEvaluation was used before: on
    // triangles it took the neighbouring cell for points near an edge
    // (1 in 16 of the reference's quadrature points on blocks P1, up to
    // 58 % of max |sigma| off, found by a walkthrough with a standalone
    // check), and missed a few points on several ranks.
    std::vector<std::optional<Gradient>>
    owned_cell_gradients(const ElasticBody           &body,
                         const GridTools::Cache<2>   &cache,
                         const std::vector<Point<2>> &points)
    {
      const auto &tree = cache.get_locally_owned_cell_bounding_boxes_rtree();
      // The points of each cell, with their unit points, so that each
      // cell is evaluated once for all of its points.
      std::map<unsigned int,
               std::pair<Triangulation<2>::active_cell_iterator,
                         std::vector<std::pair<unsigned int, Point<2>>>>>
        by_cell;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          std::vector<
            std::pair<BoundingBox<2>, Triangulation<2>::active_cell_iterator>>
            candidates;
          tree.query(boost::geometry::index::intersects(points[i]),
                     std::back_inserter(candidates));
          for (const auto &candidate : candidates)
            {
              const auto &cell = candidate.second;
              Point<2>    unit;
              try
                {
                  unit =
                    body.mapping().transform_real_to_unit_cell(cell, points[i]);
                }
              catch (const Mapping<2>::ExcTransformationFailed &)
                {
                  continue;
                }
              if (!cell->reference_cell().contains_point(unit, 1e-10))
                continue;
              auto &entry = by_cell[cell->active_cell_index()];
              entry.first = cell;
              entry.second.emplace_back(i, unit);
              break;
            }
        }

      std::vector<std::optional<Gradient>> result(points.size());
      const FEValuesExtractors::Vector     u(0);
      std::vector<Tensor<2, 2>>            gradients;
      for (const auto &[index, entry] : by_cell)
        {
          (void)index;
          std::vector<Point<2>> units;
          for (const auto &point : entry.second)
            units.push_back(point.second);
          FEValues<2> fe_values(body.mapping(),
                                body.dof_handler().get_fe(),
                                Quadrature<2>(units),
                                update_gradients);
          fe_values.reinit(
            DoFHandler<2>::active_cell_iterator(&body.triangulation(),
                                                entry.first->level(),
                                                entry.first->index(),
                                                &body.dof_handler()));
          gradients.resize(units.size());
          fe_values[u].get_function_gradients(body.solution(), gradients);
          for (unsigned int k = 0; k < units.size(); ++k)
            {
              Gradient g;
              for (unsigned int c = 0; c < 2; ++c)
                g[c] = gradients[k][c];
              result[entry.second[k].first] = g;
            }
        }
      return result;
    }



    // The gradient at each of @p points, which lie anywhere in the body:
    // those outside this rank's owned cells are answered by the rank that
    // owns their cell (every rank looks for every rank's missing points).
    std::vector<Gradient>
    gradients_at(const ElasticBody &body, const std::vector<Point<2>> &points)
    {
      const MPI_Comm comm = body.triangulation().get_communicator();
      // One tree of the owned cells for this rank's points and the others'.
      const GridTools::Cache<2> cache(body.triangulation(), body.mapping());
      const auto result = owned_cell_gradients(body, cache, points);
      std::vector<unsigned int> missing;
      std::vector<Point<2>>     wanted;
      for (unsigned int i = 0; i < points.size(); ++i)
        if (!result[i])
          {
            missing.push_back(i);
            wanted.push_back(points[i]);
          }
      // Per wanted point of every rank: found here (1 or 0), gradient.
      const auto all_wanted = Utilities::MPI::all_gather(comm, wanted);
      std::vector<std::vector<double>> answers(all_wanted.size());
      for (unsigned int rank = 0; rank < all_wanted.size(); ++rank)
        for (const auto &g :
             owned_cell_gradients(body, cache, all_wanted[rank]))
          answers[rank].insert(answers[rank].end(),
                               {g ? 1. : 0.,
                                g ? (*g)[0][0] : 0.,
                                g ? (*g)[0][1] : 0.,
                                g ? (*g)[1][0] : 0.,
                                g ? (*g)[1][1] : 0.});
      const unsigned int my_rank = Utilities::MPI::this_mpi_process(comm);
      std::vector<std::optional<Gradient>> found(missing.size());
      for (const auto &from : Utilities::MPI::all_gather(comm, answers))
        for (unsigned int k = 0; k < missing.size(); ++k)
          if (!found[k] && from[my_rank][5 * k] == 1.)
            {
              Gradient g;
              for (unsigned int c = 0; c < 2; ++c)
                for (unsigned int d = 0; d < 2; ++d)
                  g[c][d] = from[my_rank][5 * k + 1 + 2 * c + d];
              found[k] = g;
            }

      std::vector<Gradient> gradients(points.size());
      for (unsigned int i = 0; i < points.size(); ++i)
        if (result[i])
          gradients[i] = *result[i];
      for (unsigned int k = 0; k < missing.size(); ++k)
        {
          AssertThrow(found[k],
                      ExcMessage("An evaluation point of body '" + body.name() +
                                 "' lies outside the reference mesh."));
          gradients[missing[k]] = *found[k];
        }
      return gradients;
    }
  } // namespace



  ReferenceSolutionStress::ReferenceSolutionStress(
    const Scene                              &scene,
    const Parameters                         &parameters,
    const std::array<const ElasticBody *, 2> &judged,
    const unsigned int                        refinements,
    const bool                                estimate_own_error)
    : quiet(std::cout, false)
    , refinements(refinements)
  {
    AssertThrow(refinements >= 1,
                ExcMessage("a reference needs at least one refinement"));
    for (unsigned int b = 0; b < 2; ++b)
      bodies[b] =
        make_refined_body(*judged[b], scene, b, parameters, refinements);
    n_newton_iterations = solve_quietly(bodies, parameters, quiet);
    for (unsigned int b = 0; b < 2; ++b)
      energies[b] =
        coulomb_adapt::strain_energy(*bodies[b], bodies[b]->solution());
    if (!estimate_own_error)
      return;

    // One level coarser: the judged FE solution, or a body of its own.
    std::array<std::unique_ptr<ElasticBody>, 2> coarser;
    std::array<const ElasticBody *, 2>          coarser_bodies = judged;
    if (refinements > 1)
      {
        for (unsigned int b = 0; b < 2; ++b)
          coarser[b] = make_refined_body(
            *judged[b], scene, b, parameters, refinements - 1);
        solve_quietly(coarser, parameters, quiet);
        coarser_bodies = body_pointers(coarser);
      }
    const StressDifference d =
      compare_stresses(coarser_bodies,
                       {{&coarser_bodies[0]->solution(),
                         &coarser_bodies[1]->solution()}},
                       *this,
                       2);
    epsilon_own =
      std::sqrt(d.difference_squared / std::max(d.sum_squared, 1e-300));
    double coarser_energy = 0;
    for (unsigned int b = 0; b < 2; ++b)
      coarser_energy +=
        coulomb_adapt::strain_energy(*coarser_bodies[b],
                                     coarser_bodies[b]->solution());
    const double energy = energies[0] + energies[1];
    epsilon_own_energy  = std::sqrt(std::abs(energy - coarser_energy) /
                                   std::max(4 * energy, 1e-300));
  }



  ReferenceSolutionStress::~ReferenceSolutionStress() = default;



  std::vector<SymmetricTensor<2, 2>>
  ReferenceSolutionStress::stresses(const unsigned int           b,
                                    const std::vector<Point<2>> &points) const
  {
    const ElasticBody                 &body      = *bodies[b];
    const auto                         gradients = gradients_at(body, points);
    std::vector<SymmetricTensor<2, 2>> sigma(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        Tensor<2, 2> gradient;
        for (unsigned int c = 0; c < 2; ++c)
          gradient[c] = gradients[i][c];
        sigma[i] = body.material().stress(symmetrize(gradient));
      }
    return sigma;
  }



  unsigned int
  ReferenceSolutionStress::quadrature_subdivisions() const
  {
    return 1u << refinements;
  }



  std::string
  ReferenceSolutionStress::description() const
  {
    return "reference solution (the judged meshes refined " +
           std::to_string(refinements) + " times, " + std::to_string(n_dofs()) +
           " DoFs)";
  }



  unsigned int
  ReferenceSolutionStress::newton_iterations() const
  {
    return n_newton_iterations;
  }



  types::global_dof_index
  ReferenceSolutionStress::n_dofs() const
  {
    return bodies[0]->dof_handler().n_dofs() +
           bodies[1]->dof_handler().n_dofs();
  }



  const ElasticBody &
  ReferenceSolutionStress::body(const unsigned int b) const
  {
    return *bodies[b];
  }



  double
  ReferenceSolutionStress::strain_energy(const unsigned int b) const
  {
    return energies[b];
  }



  unsigned int
  ReferenceSolutionStress::n_refinements() const
  {
    return refinements;
  }



  double
  ReferenceSolutionStress::own_error() const
  {
    return epsilon_own;
  }



  double
  ReferenceSolutionStress::own_error_from_energy() const
  {
    return epsilon_own_energy;
  }
} // namespace coulomb_adapt
