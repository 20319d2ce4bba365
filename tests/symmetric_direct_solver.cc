// solve_symmetric_positive_definite (solvers/symmetric_direct_solver.h):
// MUMPS's LDL^T of the lower triangle, the CRE estimator's parameters'
// system (Estimator = cre). Checked on the SPD system of a P2 reaction-
// diffusion problem on a distributed mesh (a few thousand unknowns, split
// between the ranks of a 2-rank run), against what must hold for any
// correct solve:
//
// - the backward error |A x - b| / (|A|_F |x|) is round-off (1e-16);
// - x agrees with MUMPS's LU of the whole matrix through Amesos (the
//   solver it replaced) to 1e-12 relative, so the lower triangle is read
//   and the unknowns are gathered and scattered back in the right order;
// - the solve is linear in b: b * 1000 gives x * 1000 to 1e-14 relative
//   (the factorisation does not depend on b; the CRE estimate's
//   homogeneity test rests on it);
// - a matrix that is singular (a zero row and column) is reported with
//   MUMPS's error code, on every rank, not returned as a solution.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_solver.h>

#include <coulomb_adapt/solvers/symmetric_direct_solver.h>

#include "test_utilities.h"

#include <cmath>
#include <string>

using namespace coulomb_adapt;

namespace
{
  struct System
  {
    TrilinosWrappers::SparseMatrix A;
    TrilinosWrappers::MPI::Vector  b;
  };

  // -Laplace u + u on the unit square, P2 on 16 x 16 squares: symmetric
  // positive definite, with an irregular load (not aligned with any
  // eigenvector) so that every unknown takes part.
  System
  reaction_diffusion_system(const MPI_Comm comm)
  {
    parallel::distributed::Triangulation<2> triangulation(comm);
    GridGenerator::hyper_cube(triangulation);
    triangulation.refine_global(4);
    const FE_Q<2> fe(2);
    DoFHandler<2> dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    const IndexSet owned = dof_handler.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    DynamicSparsityPattern dsp(relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp);
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);

    System system;
    system.A.reinit(owned, owned, dsp, comm);
    system.b.reinit(owned, comm);
    const QGauss<2>                      quadrature(3);
    FEValues<2>                          fe_values(fe,
                          quadrature,
                          update_values | update_gradients |
                            update_quadrature_points | update_JxW_values);
    const unsigned int                   n = fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> indices(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          cell_rhs    = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Point<2> &x    = fe_values.quadrature_point(q);
              const double    load = std::sin(7 * x[0]) + x[1] * x[1] * x[0];
              for (unsigned int i = 0; i < n; ++i)
                {
                  for (unsigned int j = 0; j < n; ++j)
                    cell_matrix(i, j) +=
                      (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q) +
                       fe_values.shape_value(i, q) *
                         fe_values.shape_value(j, q)) *
                      fe_values.JxW(q);
                  cell_rhs(i) +=
                    load * fe_values.shape_value(i, q) * fe_values.JxW(q);
                }
            }
          cell->get_dof_indices(indices);
          system.A.add(indices, cell_matrix);
          system.b.add(indices, cell_rhs);
        }
    system.A.compress(VectorOperation::add);
    system.b.compress(VectorOperation::add);
    return system;
  }



  double
  relative_residual(const System                        &system,
                    const TrilinosWrappers::MPI::Vector &x)
  {
    TrilinosWrappers::MPI::Vector residual(system.b);
    system.A.vmult(residual, x);
    residual -= system.b;
    return residual.l2_norm() / (system.A.frobenius_norm() * x.l2_norm());
  }



  double
  relative_difference(const TrilinosWrappers::MPI::Vector &x,
                      const TrilinosWrappers::MPI::Vector &y)
  {
    TrilinosWrappers::MPI::Vector difference(x);
    difference -= y;
    return difference.l2_norm() / y.l2_norm();
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  System                        system = reaction_diffusion_system(comm);
  TrilinosWrappers::MPI::Vector x(system.b);
  solve_symmetric_positive_definite(system.A, x, system.b);
  out << "unknowns: " << system.A.m() << std::endl;
  const double residual = relative_residual(system, x);
  out << "backward error |A x - b| / (|A|_F |x|) below 1e-16: "
      << (residual < 1e-16 ? "yes" : "no") << std::endl;

  TrilinosWrappers::MPI::Vector                  x_lu(system.b);
  SolverControl                                  control(1, 0);
  TrilinosWrappers::SolverDirect::AdditionalData data(false, "Amesos_Mumps");
  TrilinosWrappers::SolverDirect                 lu(control, data);
  lu.initialize(system.A);
  lu.solve(x_lu, system.b);
  const double difference = relative_difference(x, x_lu);
  out << "agrees with Amesos' LU to 1e-12: "
      << (difference < 1e-12 ? "yes" : "no") << std::endl;

  TrilinosWrappers::MPI::Vector b_scaled(system.b), x_scaled(system.b);
  b_scaled *= 1000.;
  solve_symmetric_positive_definite(system.A, x_scaled, b_scaled);
  x_scaled /= 1000.;
  const double scaling = relative_difference(x_scaled, x);
  out << "b * 1000 gives x * 1000 to 1e-14: "
      << (scaling < 1e-14 ? "yes" : "no") << std::endl;

  // Singular: the first row and column set to zero.
  const types::global_dof_index first = 0;
  if (system.A.in_local_range(first))
    for (auto entry = system.A.begin(first); entry != system.A.end(first);
         ++entry)
      entry->value() = 0;
  for (const auto i : system.A.locally_owned_range_indices())
    if (system.A.el(i, first) != 0)
      system.A.set(i, first, 0.);
  system.A.compress(VectorOperation::insert);
  try
    {
      solve_symmetric_positive_definite(system.A, x, system.b);
      out << "singular matrix: no error" << std::endl;
    }
  catch (const std::exception &error)
    {
      // deal.II wraps the message's lines: join them.
      std::string message;
      for (const char c : std::string(error.what()))
        if (c != '\n' &&
            !(c == ' ' && !message.empty() && message.back() == ' '))
          message += c;
      out << "singular matrix: INFOG(1) = -10 reported: "
          << (message.find("INFOG(1) = -10,") != std::string::npos ? "yes" :
                                                                     "no")
          << ", 'numerically singular' said: "
          << (message.find("the matrix is numerically singular") !=
                  std::string::npos ?
                "yes" :
                "no")
          << std::endl;
    }

  AssertThrow(residual < 1e-13,
              ExcMessage("residual " + std::to_string(residual)));
  AssertThrow(difference < 1e-12,
              ExcMessage("difference to LU " + std::to_string(difference)));
  AssertThrow(scaling < 1e-14,
              ExcMessage("scaling " + std::to_string(scaling)));
}
