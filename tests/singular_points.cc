// The singular points of the optimal mesh (theory.md section 4) come from
// the scene's description of its boundary parts, not from the built-in
// scenes' boundary ids: the gmsh scene on prm/blocks_gmsh.prm (the seed's
// blocks as gmsh curves, the same vertices as the built-in scene) has the
// built-in scene's singular points, the ends of the contact faces and the
// corners of the clamped base:
//   upper block: (50, 200), (150, 200), where the contact face ends;
//   lower block: (0, 200), (200, 200), the same, and (0, 0), (200, 0),
//   where the clamped base meets the free sides.
// The same with the base clamped at a prescribed displacement (x = 0,
// y = 0.001 mm): the gmsh scene gives such a group a boundary id of its
// own (3 and up, not the id 2 of a zero clamp), whose corners were lost
// while the adaptation looked for the built-in scenes' ids.

#include <coulomb_adapt/adaptation/optimal_size.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  std::vector<Point<2>>
  singular_points(
    const std::vector<std::pair<std::string, std::string>> &settings,
    const std::string                                      &parameter_file)
  {
    const auto p = testing::solve_contact_setup(settings, parameter_file);
    return find_singular_points({{p->bodies[0].get(), p->bodies[1].get()}}, {});
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const auto        built_in = singular_points({{"Scene/Name", "blocks"}}, "");
  const std::string geo = testing::example_file("meshes/blocks_structured.geo");
  const std::string prm = testing::example_file("blocks_gmsh.prm");
  const auto gmsh       = singular_points({{"Scene/Gmsh/Mesh file", geo}}, prm);
  const auto moved_base =
    singular_points({{"Scene/Gmsh/Mesh file", geo},
                     {"Scene/Gmsh/Fixed components", "base: x y=0.001"}},
                    prm);

  const std::vector<Point<2>> expected = {
    {0, 0}, {0, 200}, {50, 200}, {150, 200}, {200, 0}, {200, 200}};
  for (const auto &[name, points] :
       std::vector<std::pair<std::string, std::vector<Point<2>>>>{
         {"blocks", built_in},
         {"gmsh", gmsh},
         {"gmsh, base moved", moved_base}})
    {
      out << name << ": " << points.size() << " singular points:";
      for (const Point<2> &x : points)
        out << " (" << x[0] << ", " << x[1] << ")";
      out << std::endl;
      AssertThrow(points.size() == expected.size(),
                  ExcMessage(name + ": wrong number of points"));
      // find_singular_points returns them ordered by (x, y).
      for (unsigned int i = 0; i < points.size(); ++i)
        AssertThrow(points[i].distance(expected[i]) < 1e-10,
                    ExcMessage(name + ": a point differs"));
    }
  return 0;
}
