#include <deal.II/grid/grid_generator.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

namespace coulomb_adapt
{
  void
  make_rectangle(Triangulation<2>                        &tria,
                 const Point<2>                          &p1,
                 const Point<2>                          &p2,
                 const std::vector<unsigned int>         &subdivisions,
                 const std::array<types::boundary_id, 4> &side_ids,
                 const CellType                           cell_type)
  {
    Triangulation<2> quads;
    // colorize: ids 0, 1, 2, 3 on the left, right, bottom, top sides.
    GridGenerator::subdivided_hyper_rectangle(
      quads, subdivisions, p1, p2, /*colorize=*/true);
    for (const auto &cell : quads.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          face->set_boundary_id(side_ids[face->boundary_id()]);

    tria.clear();
    if (cell_type == CellType::quadrilateral)
      tria.copy_triangulation(quads);
    else
      GridGenerator::convert_hypercube_to_simplex_mesh(quads, tria);
  }



  std::vector<unsigned int>
  get_subdivisions(ParameterHandler  &prm,
                   const std::string &entry,
                   const std::string &path)
  {
    const std::vector<std::string> words =
      Utilities::split_string_list(prm.get(entry));
    std::vector<unsigned int> n;
    for (const auto &w : words)
      n.push_back(Utilities::string_to_int(w));
    if (n.size() != 2 || n[0] < 1 || n[1] < 1)
      throw ParameterError(path + "/" + entry,
                           prm.get(entry),
                           "expected two positive integers 'nx, ny'");
    return n;
  }



  void
  refine_towards_point(Triangulation<2> &tria,
                       const Point<2>   &point,
                       const double      radius,
                       const double      target_size)
  {
    // Refine until the edges of the cells near the point are no longer
    // than the target.
    const auto longest_edge = [](const auto &cell) {
      double h = 0;
      for (const auto &face : cell->face_iterators())
        h = std::max(h, face->measure());
      return h;
    };
    for (unsigned int step = 0; step < 30; ++step)
      {
        bool any = false;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned() &&
              cell->center().distance(point) < radius + cell->diameter() &&
              longest_edge(cell) > target_size)
            {
              cell->set_refine_flag();
              any = true;
            }
        if (Utilities::MPI::logical_or(any, tria.get_communicator()) == false)
          break;
        tria.execute_coarsening_and_refinement();
      }
  }
} // namespace coulomb_adapt
