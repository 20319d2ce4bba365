// The stiffness matrix and load of ElasticBody::assemble_system() do not
// depend on the number of threads beyond round-off: the cells run on
// deal.II's threads (WorkStream) and are added in their order, so 1 thread
// and up to 4 give the same matrix and load to 1e-13 (relative, Frobenius
// and l2 norms of the change). Not bit for bit: FEValues reuses the
// geometry of a previous cell that the current one is a translate of, and
// each thread has its own previous cell, so a recomputed Jacobian can
// differ in its last bit (measured: 7e-16 on the manufactured P1 lower
// square; two 1-thread assemblies are identical). A race between the
// threads (shared scratch) or a lost cell changes the matrix by far more:
// one cell of n is about n^(-1/2) of its norm. Scenes: 'manufactured' (a
// body force, two materials) and 'blocks' (a traction on the upper
// block's top), on triangles P1, P2 and quadrilaterals Q1, Q2, both
// bodies, two global refinements; 1 and 2 ranks.
//
// The strain energy (strain_energy(), summary.json's strain_energy of
// every cycle) runs on the threads the same way. It is checked on a
// displacement linear in x, whose strain eps is constant and held by every
// element space here: U = 1/2 |Omega| sigma(eps) : eps exactly, |Omega|
// the sum of the cells' measures. With 1 thread and with up to 4 it
// must match that to 1e-12 and each other to 1e-13; a lost or doubled
// cell changes it by about 1/n.

#include <deal.II/base/function.h>
#include <deal.II/base/multithread_info.h>

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>

using namespace coulomb_adapt;

namespace
{
  // The largest of the relative changes of the matrix (Frobenius norm)
  // and the load (l2 norm) from @p matrix and @p rhs.
  double
  relative_change(const ElasticBody                    &body,
                  const TrilinosWrappers::SparseMatrix &matrix,
                  const TrilinosWrappers::MPI::Vector  &rhs)
  {
    TrilinosWrappers::SparseMatrix matrix_change;
    matrix_change.copy_from(body.system_matrix());
    matrix_change.add(-1., matrix);
    TrilinosWrappers::MPI::Vector rhs_change(body.system_rhs());
    rhs_change -= rhs;
    return std::max(matrix_change.frobenius_norm() / matrix.frobenius_norm(),
                    rhs.l2_norm() > 0 ? rhs_change.l2_norm() / rhs.l2_norm() :
                                        rhs_change.l2_norm());
  }



  // u = (0.3 x - 0.2 y, 0.1 x + 0.4 y) * 1e-3: eps_xx = 3e-4,
  // eps_yy = 4e-4, eps_xy = -0.5e-4.
  class LinearDisplacement : public Function<2>
  {
  public:
    LinearDisplacement()
      : Function<2>(2)
    {}

    double
    value(const Point<2> &p, const unsigned int component) const override
    {
      return component == 0 ? 1e-3 * (0.3 * p[0] - 0.2 * p[1]) :
                              1e-3 * (0.1 * p[0] + 0.4 * p[1]);
    }
  };



  // Whether strain_energy() of the linear displacement is the exact one
  // to 1e-12 with 1 thread and with up to 4, and the same for both to
  // 1e-13.
  bool
  strain_energy_exact_on_any_thread_count(const ElasticBody &body)
  {
    TrilinosWrappers::MPI::Vector owned(body.locally_owned_dof_set(),
                                        MPI_COMM_WORLD);
    VectorTools::interpolate(body.mapping(),
                             body.dof_handler(),
                             LinearDisplacement(),
                             owned);
    TrilinosWrappers::MPI::Vector displacement(body.locally_owned_dof_set(),
                                               body.locally_relevant_dof_set(),
                                               MPI_COMM_WORLD);
    displacement = owned;

    SymmetricTensor<2, 2> strain;
    strain[0][0] = 3e-4;
    strain[1][1] = 4e-4;
    strain[0][1] = -0.5e-4;
    // |Omega| from the owned cells' measures (from their vertices). Not
    // deal.II 9.4's GridTools::volume with the body's mapping: on these
    // triangle meshes it gave exactly twice the area (measured).
    double area = 0;
    for (const auto &cell : body.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        area += cell->measure();
    area               = Utilities::MPI::sum(area, MPI_COMM_WORLD);
    const double exact = 0.5 * area * (body.material().stress(strain) * strain);

    MultithreadInfo::set_thread_limit(1);
    const double one_thread = strain_energy(body, displacement);
    MultithreadInfo::set_thread_limit(4);
    const double threads = strain_energy(body, displacement);
    MultithreadInfo::set_thread_limit(1);
    return std::abs(one_thread - exact) <= 1e-12 * exact &&
           std::abs(threads - exact) <= 1e-12 * exact &&
           std::abs(threads - one_thread) <= 1e-13 * exact;
  }



  void
  check(const std::string &scene_name,
        const std::string &cell_type,
        const unsigned int degree)
  {
    ParameterHandler prm;
    const Parameters parameters =
      testing::make_parameters(prm,
                               {{"Scene/Name", scene_name},
                                {"Mesh/Cell type", cell_type},
                                {"Finite elements/Polynomial degree",
                                 std::to_string(degree)}});
    const auto scene = scenes::create_scene(parameters, prm);
    auto       out   = testing::root_output();
    for (unsigned int b = 0; b < 2; ++b)
      {
        ElasticBody body(MPI_COMM_WORLD,
                         *scene,
                         b,
                         parameters.mesh.cell_type,
                         2,
                         parameters.finite_elements);
        body.setup_system();

        MultithreadInfo::set_thread_limit(1);
        body.assemble_system();
        TrilinosWrappers::SparseMatrix one_thread;
        one_thread.copy_from(body.system_matrix());
        const TrilinosWrappers::MPI::Vector one_thread_rhs(body.system_rhs());

        MultithreadInfo::set_thread_limit(4);
        AssertThrow(MultithreadInfo::n_threads() > 1,
                    ExcMessage("this check needs more than one thread: "
                               "DEAL_II_NUM_THREADS limits them to 1"));
        body.assemble_system();
        const bool same =
          relative_change(body, one_thread, one_thread_rhs) <= 1e-13;
        MultithreadInfo::set_thread_limit(1);

        // A load that is zero would compare trivially.
        const bool loaded = one_thread_rhs.l2_norm() > 0;
        out << scene_name << ", " << (cell_type == "triangle" ? "P" : "Q")
            << degree << ", " << body.name() << ": "
            << body.dof_handler().n_dofs()
            << " DoFs, matrix and load with up to 4 threads those of 1 to "
               "1e-13: "
            << (same ? "yes" : "no")
            << (loaded ? "" : " (the load is zero: the body has no load)")
            << std::endl;
        AssertThrow(same,
                    ExcMessage("the assembly depends on the thread count"));

        const bool energy = strain_energy_exact_on_any_thread_count(body);
        out << "  strain energy of a linear displacement with 1 and with up "
               "to 4 threads the exact 1/2 |Omega| sigma:eps to 1e-12: "
            << (energy ? "yes" : "no") << std::endl;
        AssertThrow(energy,
                    ExcMessage("the strain energy is not the exact one on "
                               "every thread count"));
      }
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const std::string scene : {"manufactured", "blocks"})
    for (const std::string cell_type : {"triangle", "quadrilateral"})
      for (const unsigned int degree : {1u, 2u})
        check(scene, cell_type, degree);
  return 0;
}
