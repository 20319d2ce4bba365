// near_singular_point (adaptation/optimal_size.h): a cell takes the
// singular rate when the singular point lies in it or closer to it than
// half its diameter, the distance measured to its straight faces.
// Expected values by hand:
//  - the triangle (0, 0), (1, 0), (0, 1): diameter sqrt(2), reach
//    sqrt(2)/2 = 0.7071. Near: a vertex, a point on an edge, an inner
//    point, (-0.7, 0) (0.7 from the vertex (0, 0)), (0.95, 0.95) (in the
//    bounding box, 0.6364 from the hypotenuse). Not near: (-0.72, 0)
//    (0.72), (0, 1.71) (0.71 beyond the top vertex), (1.2, 1.2) (0.9899
//    from the hypotenuse, although only 0.2828 from the bounding box).
//  - the square [0, 1]^2: diameter sqrt(2). Near: (1.7, 0.5) (0.7 from
//    the right face), (1.45, 1.45) (0.6364 from the corner). Not near:
//    (1.72, 0.5), (1.55, 1.55) (0.7778 from the corner).
// 1 rank.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>

#include <coulomb_adapt/adaptation/optimal_size.h>

#include "test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  void
  check(ConditionalOStream                           &out,
        const std::string                            &cell_name,
        const Triangulation<2>::active_cell_iterator &cell,
        const Point<2>                               &p,
        const bool                                    expected)
  {
    const bool near = near_singular_point(cell, p);
    out << cell_name << ", point (" << p
        << "): " << (near ? "near" : "not near") << std::endl;
    AssertThrow(near == expected,
                ExcMessage(cell_name + ": wrong answer for a point"));
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  Triangulation<2>         triangle;
  std::vector<CellData<2>> cells(1);
  cells[0].vertices = {0, 1, 2};
  triangle.create_triangulation(
    {Point<2>(0, 0), Point<2>(1, 0), Point<2>(0, 1)}, cells, SubCellData());
  const auto t = triangle.begin_active();
  AssertThrow(t->reference_cell() == ReferenceCells::Triangle,
              ExcInternalError());
  for (const auto &[p, expected] :
       std::vector<std::pair<Point<2>, bool>>{{{0, 0}, true},
                                              {{0.5, 0}, true},
                                              {{0.25, 0.25}, true},
                                              {{-0.7, 0}, true},
                                              {{0.95, 0.95}, true},
                                              {{-0.72, 0}, false},
                                              {{0, 1.71}, false},
                                              {{1.2, 1.2}, false}})
    check(out, "triangle", t, p, expected);

  Triangulation<2> square;
  GridGenerator::hyper_cube(square, 0, 1);
  for (const auto &[p, expected] :
       std::vector<std::pair<Point<2>, bool>>{{{1.7, 0.5}, true},
                                              {{1.45, 1.45}, true},
                                              {{1.72, 0.5}, false},
                                              {{1.55, 1.55}, false}})
    check(out, "square", square.begin_active(), p, expected);
}
