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
//    singular.
// The rigid-motion test itself: ElasticBody::support_gram of the held
// axis (a vertical line of x-constraints) holds the x translation and the
// rotation but not the y translation, about any centre.
// 1 rank.

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

namespace
{
  void
  check(const std::string &name,
        const std::string &mesh_size,
        const std::string &hold_axis,
        const bool         expect_free,
        ConditionalOStream &out)
  {
    const auto p =
      testing::solve_contact({{"Scene/Name", "hertz"},
                              {"Scene/Hertz/Hold axis", hold_axis},
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

  check("hertz, contact mesh 5 a, no hold", "5", "false", true, out);
  check("hertz, contact mesh 5 a, axis held", "5", "true", false, out);
  check("hertz, contact mesh 0.5 a, no hold", "0.5", "false", false, out);

  // Only the held axis: rows (1, 0, -(y - y0)) for the axis nodes.
  const auto p = testing::solve_contact_setup(
    {{"Scene/Name", "hertz"}, {"Scene/Hertz/Hold axis", "true"}});
  for (const Point<2> centre : {Point<2>(0, 0), Point<2>(0, 50)})
    {
      FullMatrix<double> gram = p->bodies[0]->support_gram(centre);
      AssertThrow(gram(1, 1) == 0 && gram(0, 1) == 0 && gram(1, 2) == 0,
                  ExcMessage("the axis holds a y translation"));
      AssertThrow(!holds_all_rigid_motions(gram), ExcInternalError());
      // A single vertical constraint at a point off the axis completes it.
      gram(1, 1) += 1;
      gram(1, 2) += 10 - centre[0];
      gram(2, 1) += 10 - centre[0];
      gram(2, 2) += (10 - centre[0]) * (10 - centre[0]);
      AssertThrow(holds_all_rigid_motions(gram), ExcInternalError());
    }
  out << "held axis: x translation and rotation held, y translation free; "
         "one vertical constraint off the axis holds all"
      << std::endl;
}
