// A body that nothing holds but its contact nodes can turn about a single
// active node: the Newton system is singular (ContactSolver::
// slave_rotation_free). hertz without 'Hold axis' on a contact mesh
// coarser than the contact zone rests on one stick node; the balanced load
// still has solutions, so the iteration converges, but the solver must say
// that body 1's displacement is fixed only up to a rotation. It must not
// say so where something holds the rotation:
//  - 'Contact mesh size' = 5 (elements of 5 a): one active node, rotation
//    free;
//  - the same with 'Hold axis' (the axis nodes' x displacement fixed): held;
//  - 'Contact mesh size' = 0.5 without 'Hold axis': several active nodes,
//    held, although the first step (the initial gap touches one node) was
//    singular;
//  - 'Line load' = 1e-7 without 'Hold axis': 23 stick nodes in a contact
//    zone 1e-5 wide, held (judged about the mean slave node, 100 mm away,
//    the zone looked like a point and was reported free).
// The rigid-motion test itself (rigid_motion_gram.h): ElasticBody::
// support_gram of the held axis (a vertical line of x-constraints) holds
// the x translation and the rotation but not the y translation, about
// centres on and off the axis, and equals its origin-centred matrix moved
// by move_rotation_centre; two normal constraints 1e-6 apart, 1e3 away
// from the centre, hold the rotation, one alone does not.
// 1 rank.

#include <coulomb_adapt/bodies/rigid_motion_gram.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  void
  check(const std::string  &name,
        const std::string  &mesh_size,
        const std::string  &hold_axis,
        const std::string  &line_load,
        const bool          expect_free,
        ConditionalOStream &out)
  {
    const auto p =
      testing::solve_contact({{"Scene/Name", "hertz"},
                              {"Scene/Hertz/Hold axis", hold_axis},
                              {"Scene/Hertz/Line load", line_load},
                              {"Scene/Hertz/Contact mesh size", mesh_size}});
    AssertThrow(p->report.converged, ExcInternalError());
    AssertThrow(p->report.slave_rotation_free == expect_free,
                ExcMessage(name + ": rotation free reported " +
                           (p->report.slave_rotation_free ? "yes" : "no")));
    out << name << ": " << p->report.n_active << " active node(s), rotation "
        << (expect_free ? "free" : "held") << std::endl;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  check("hertz, contact mesh 5 a, no hold", "5", "false", "1000", true, out);
  check("hertz, contact mesh 5 a, axis held", "5", "true", "1000", false, out);
  check(
    "hertz, contact mesh 0.5 a, no hold", "0.5", "false", "1000", false, out);
  check("hertz, line load 1e-7, no hold", "0.1", "false", "1e-7", false, out);

  // Only the held axis: rows (1, 0, -(y - y0)) for the axis nodes.
  const auto p = testing::solve_contact_setup(
    {{"Scene/Name", "hertz"}, {"Scene/Hertz/Hold axis", "true"}});
  const FullMatrix<double> about_origin =
    p->bodies[0]->support_gram(Point<2>());
  const Tensor<1, 2> up({0., 1.});
  for (const Point<2> centre :
       {Point<2>(0, 0), Point<2>(0, 50), Point<2>(-30, 50), Point<2>(40, -20)})
    {
      FullMatrix<double>       gram = p->bodies[0]->support_gram(centre);
      const FullMatrix<double> moved =
        move_rotation_centre(about_origin, centre - Point<2>());
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          AssertThrow(std::abs(gram(a, b) - moved(a, b)) <=
                        1e-12 * about_origin.frobenius_norm(),
                      ExcMessage("move_rotation_centre differs"));
      AssertThrow(gram(1, 1) == 0 && gram(0, 1) == 0 && gram(1, 2) == 0,
                  ExcMessage("the axis holds a y translation"));
      AssertThrow(!holds_all_rigid_motions(gram), ExcInternalError());
      // A single vertical constraint at a point off the axis completes it.
      add_rigid_motion_constraint(gram, up, Point<2>(10, 0), centre);
      AssertThrow(holds_all_rigid_motions(gram), ExcInternalError());
    }

  // A cluster far from the centre: two points 1e-6 apart hold the
  // rotation, one point with both directions fixed does not.
  const Point<2>     centre(0, 0), x(1e3, 0), x_next(1e3 + 1e-6, 0);
  const Tensor<1, 2> right({1., 0.});
  FullMatrix<double> one_point(3, 3), two_points(3, 3);
  for (FullMatrix<double> *gram : {&one_point, &two_points})
    {
      add_rigid_motion_constraint(*gram, up, x, centre);
      add_rigid_motion_constraint(*gram, right, x, centre);
    }
  add_rigid_motion_constraint(two_points, up, x_next, centre);
  const Tensor<1, 2> shift = x - centre;
  AssertThrow(!holds_all_rigid_motions(move_rotation_centre(one_point, shift)),
              ExcMessage("one point holds the rotation"));
  AssertThrow(holds_all_rigid_motions(move_rotation_centre(two_points, shift)),
              ExcMessage("two points do not hold the rotation"));
  out << "held axis: x translation and rotation held, y translation free, "
         "about four centres; one vertical constraint off the axis holds "
         "all; two points 1e-6 apart hold the rotation, one does not"
      << std::endl;
}
