#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/bodies/coarse_cell_indexed_triangulation.h>
#include <coulomb_adapt/bodies/consistent_refinement_flags.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/rigid_motion_gram.h>
#include <coulomb_adapt/bodies/triangle_mesh_description.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace coulomb_adapt
{
  // The meshes of a body: built from the scene's coarse mesh, refined,
  // adapted or replaced by a remeshed one, each checked for cells that
  // would make a singular stiffness matrix.

  // A cell with a non-finite vertex, or with no area (a repeated node, a
  // zero-area triangle), makes a singular or
  // non-finite stiffness matrix: the solver then reports garbage (a
  // MUMPS dump, "body 1 is not held") or a wrong equilibrium. Every rank
  // holds the whole coarse or remeshed mesh, so every rank stops alike.
  //
  // The message is composed only for a bad cell: composing it for every
  // cell (an ostringstream and the vertices printed) took about a third
  // of the time of building a remeshed body's mesh (benchmarks/
  // adaptive_run). @p polygon: the cell's n vertices in order around it.
  void
  check_cell(const std::array<Point<2>, 4> &polygon,
             const unsigned int             n,
             const std::string             &name,
             const unsigned int             body_index)
  {
    bool   finite   = true;
    double diameter = 0, area = 0;
    for (unsigned int v = 0; v < n; ++v)
      {
        const Point<2> &a = polygon[v];
        const Point<2> &b = polygon[(v + 1) % n];
        finite = finite && std::isfinite(a[0]) && std::isfinite(a[1]);
        for (unsigned int w = 0; w < n; ++w)
          diameter = std::max(diameter, a.distance(polygon[w]));
        area += a[0] * b[1] - b[0] * a[1];
      }
    area /= 2;
    // Well below the round-off of the diameter squared there is no
    // area (either orientation: gmsh's triangles may run clockwise).
    if (finite && std::abs(area) > 1e-12 * diameter * diameter)
      return;
    std::ostringstream where;
    where << "the mesh of body " << body_index + 1 << " (" << name
          << ") has a cell with the vertices";
    for (unsigned int v = 0; v < n; ++v)
      where << (v == 0 ? " (" : ", (") << polygon[v][0] << ", " << polygon[v][1]
            << ")";
    if (!finite)
      throw std::runtime_error(where.str() + ": a coordinate is not a finite "
                                             "number");
    throw std::runtime_error(
      where.str() +
      ": it has no area (a repeated node, or its vertices on one "
      "line)" +
      "; the stiffness matrix of such a cell is singular. Fix the "
      "mesh");
  }



  void
  check_mesh_cells(const Triangulation<2> &mesh,
                   const std::string      &name,
                   const unsigned int      body_index)
  {
    for (const auto &cell : mesh.active_cell_iterators())
      {
        const unsigned int n = cell->n_vertices();
        if (n == 3)
          check_cell({{cell->vertex(0), cell->vertex(1), cell->vertex(2)}},
                     3,
                     name,
                     body_index);
        else
          check_cell({{cell->vertex(0),
                       cell->vertex(1),
                       cell->vertex(3),
                       cell->vertex(2)}},
                     4,
                     name,
                     body_index);
      }
  }



  // The same for a remeshed body's triangles.
  void
  check_mesh_cells(const CoarseMeshData &mesh,
                   const std::string    &name,
                   const unsigned int    body_index)
  {
    for (const auto &cell : mesh.cells)
      check_cell({{mesh.vertices[cell.vertices[0]],
                   mesh.vertices[cell.vertices[1]],
                   mesh.vertices[cell.vertices[2]]}},
                 3,
                 name,
                 body_index);
  }



  // A fully distributed triangle mesh from @p description, with the
  // manifolds of @p scene_mesh (the scene's coarse mesh, or its refinement:
  // the remesher copied their ids).
  std::unique_ptr<parallel::TriangulationBase<2>>
  fully_distributed_mesh(
    const TriangulationDescription::Description<2, 2> &description,
    const Triangulation<2>                            &scene_mesh)
  {
    auto t = std::make_unique<CoarseCellIndexedTriangulation>(description.comm);
    for (const auto id : scene_mesh.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        t->set_manifold(id, scene_mesh.get_manifold(id));
    t->create_triangulation(description);
    return t;
  }



  // Builds the distributed mesh. Quadrilaterals: p4est from the coarse mesh,
  // refined in place. Triangles: the serial mesh is refined, partitioned
  // and handed to a fully distributed triangulation (each rank keeps its
  // cells and a ghost layer). A remeshed body that is not refined further
  // (every cycle of 'Strategy = remesh') skips the serial mesh: its
  // description comes straight from the remesher's cells, and is the one
  // the serial mesh would give (tests/triangle_mesh_description).
  void
  ElasticBody::create_mesh(const unsigned int n_refinements)
  {
    Triangulation<2> serial;
    create_scene_coarse_mesh(serial);
    std::unique_ptr<parallel::TriangulationBase<2>> new_tria;
    if (remeshed && n_refinements == 0)
      {
        check_mesh_cells(*remeshed, body_description.name, body_index);
        simplex  = true;
        new_tria = fully_distributed_mesh(
          describe_triangle_mesh(*remeshed, mpi_communicator), serial);
      }
    else
      new_tria = mesh_through_serial_triangulation(serial, n_refinements);
    // The DoFHandler must let go of the old mesh before it is destroyed.
    dofs.reinit(*new_tria);
    tria = std::move(new_tria);
  }



  // The scene's coarse mesh (or the remeshed one) as @p serial, refined
  // n_refinements times and made distributed.
  std::unique_ptr<parallel::TriangulationBase<2>>
  ElasticBody::mesh_through_serial_triangulation(
    Triangulation<2>  &serial,
    const unsigned int n_refinements)
  {
    if (remeshed)
      {
        // Keep the scene's manifolds: the remesher copied their ids. The
        // remeshed cells go straight into the serial mesh (a second
        // triangulation and a copy of it cost as much as the check below).
        std::map<types::manifold_id, std::unique_ptr<Manifold<2>>> manifolds;
        for (const auto id : serial.get_manifold_ids())
          if (id != numbers::flat_manifold_id)
            manifolds[id] = serial.get_manifold(id).clone();
        remeshed->create_triangulation(serial);
        for (const auto &[id, manifold] : manifolds)
          serial.set_manifold(id, *manifold);
      }
    simplex = !serial.all_reference_cells_are_hyper_cube();
    check_mesh_cells(serial, body_description.name, body_index);

    if (!simplex)
      {
        auto t = std::make_unique<parallel::distributed::Triangulation<2>>(
          mpi_communicator);
        t->copy_triangulation(serial);
        // The scene's grading first, so that global refinements divide its
        // element sizes too.
        scene.refine_initial_mesh(body_index, *t);
        t->refine_global(n_refinements);
        return t;
      }
    serial.refine_global(n_refinements);
    GridTools::partition_triangulation(
      Utilities::MPI::n_mpi_processes(mpi_communicator), serial);
    return fully_distributed_mesh(
      TriangulationDescription::Utilities::
        create_description_from_triangulation(serial, mpi_communicator),
      serial);
  }



  void
  ElasticBody::refine_uniformly()
  {
    ++n_global_refinements;
    if (simplex)
      create_mesh(n_global_refinements);
    else
      tria->refine_global(1);
  }



  void
  ElasticBody::refine_and_coarsen(const std::vector<signed char> &decisions)
  {
    AssertThrow(!simplex,
                ExcMessage("local refinement needs quadrilaterals (deal.II "
                           "9.4 refines triangles only globally)"));
    // Cells to refine again after this round, by CellId (p4est may move
    // the children to another rank when it repartitions).
    std::map<CellId, int> again;
    for (const auto &cell : tria->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const signed char d = decisions[cell->active_cell_index()];
          if (d > 0)
            cell->set_refine_flag();
          else if (d < 0)
            cell->set_coarsen_flag();
          if (d > 1)
            again[cell->id()] = d - 1;
        }
    prepare_refinement_flags_consistently(*tria);
    tria->execute_coarsening_and_refinement();

    while (true)
      {
        std::map<CellId, int> all;
        for (const auto &part : Utilities::MPI::all_gather(
               mpi_communicator,
               std::vector<std::pair<CellId, int>>(again.begin(), again.end())))
          all.insert(part.begin(), part.end());
        if (all.empty())
          break;
        again.clear();
        for (const auto &cell : tria->active_cell_iterators())
          if (cell->is_locally_owned() && cell->level() > 0)
            {
              const auto parent = all.find(cell->parent()->id());
              if (parent == all.end())
                continue;
              cell->set_refine_flag();
              if (parent->second > 1)
                again[cell->id()] = parent->second - 1;
            }
        prepare_refinement_flags_consistently(*tria);
        tria->execute_coarsening_and_refinement();
      }
  }



  std::set<CellId>
  ElasticBody::refined_cells(const unsigned int below_level) const
  {
    // A cell refined on this rank's part of the mesh is refined in the
    // whole mesh (the local tree is a coarsening of the global one); the
    // union over the ranks has every refined cell.
    std::vector<CellId> local;
    for (unsigned int level = 0;
         level < std::min(below_level, tria->n_levels());
         ++level)
      for (const auto &cell : tria->cell_iterators_on_level(level))
        if (cell->has_children())
          local.push_back(cell->id());
    std::set<CellId> all;
    for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, local))
      all.insert(part.begin(), part.end());
    return all;
  }



  void
  ElasticBody::refine_as(const std::set<CellId> &refined,
                         const unsigned int      finest_level)
  {
    AssertThrow(!simplex,
                ExcMessage("local refinement needs quadrilaterals (deal.II "
                           "9.4 refines triangles only globally)"));
    while (true)
      {
        bool any = false;
        for (const auto &cell : tria->active_cell_iterators())
          if (cell->is_locally_owned() &&
              static_cast<unsigned int>(cell->level()) < finest_level &&
              refined.count(cell->id()) > 0)
            {
              cell->set_refine_flag();
              any = true;
            }
        if (!Utilities::MPI::logical_or(any, mpi_communicator))
          break;
        prepare_refinement_flags_consistently(*tria);
        tria->execute_coarsening_and_refinement();
      }
  }



  void
  ElasticBody::replace_mesh(CoarseMeshData mesh)
  {
    AssertThrow(simplex,
                ExcMessage("remeshing produces triangles; this body has "
                           "quadrilaterals"));
    remeshed             = std::move(mesh);
    n_global_refinements = 0;
    create_mesh(0);
  }



  void
  ElasticBody::create_scene_coarse_mesh(Triangulation<2> &serial) const
  {
    scene.create_coarse_mesh(body_index, cell_type, serial);
  }
} // namespace coulomb_adapt
