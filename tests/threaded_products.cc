// The products the CRE estimator's truncated CG runs on deal.II's threads
// (solvers/threaded_matrix_product.h,
// solvers/additive_schwarz_preconditioner.h) are those of one thread, bit for
// bit, so that the estimate does not depend on the number of threads through
// them. On the SPD system of a P2 reaction-diffusion problem on a distributed
// mesh (split between the ranks of a 2-rank run: the matrix then has columns of
// the other rank, which the threaded product imports):
//
// - ThreadedMatrixProduct::vmult equals TrilinosWrappers::SparseMatrix::vmult
//   (Epetra's kernel, one thread) in every entry, with 1 and 4 threads, and
//   really runs its own loop (deal.II's matrices have optimised storage);
// - the additive Schwarz preconditioner over the vertex stars, built and
//   applied with 4 threads, equals the one built and applied with 1
//   thread in every entry; its patches are the same (count, mean size);
// - a truncated CG with 4 threads takes the same steps and gives the same
//   minimiser, bit for bit, as with 1 thread;
// - the product on Epetra vectors (ReducedMatrix's bodies' products in the
//   contact solve's GMRES and AMG smoother) equals Epetra's in every entry;
// - GMRES (solve_krylov, not symmetric: deal.II's threaded vectors, the
//   contact solve's Krylov method with friction; the same problem with 6
//   refinements, 16,641 unknowns) preconditioned by the
//   same AMG reaches its tolerance in the true residual |b - A x|
//   (Epetra's product), with 1 and with 4 threads; two runs with 4 threads
//   give the same steps and solution, bit for bit; 1 and 4 threads agree
//   to round-off, not bit for bit (deal.II cuts its reductions into a
//   number of chunks that depends on the number of threads).
//
// The 2-rank run prints what the 1-rank run prints.

#include <deal.II/base/multithread_info.h>

#include <deal.II/lac/trilinos_precondition.h>

#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>
#include <coulomb_adapt/solvers/linear_solver.h>
#include <coulomb_adapt/solvers/threaded_matrix_product.h>
#include <coulomb_adapt/solvers/truncated_minimisation.h>

#include "reaction_diffusion_system.h"
#include "test_utilities.h"

#include <algorithm>
#include <cmath>

using namespace coulomb_adapt;

namespace
{
  // The largest |a_i - b_i| over all ranks.
  double
  largest_difference(const TrilinosWrappers::MPI::Vector &a,
                     const TrilinosWrappers::MPI::Vector &b)
  {
    TrilinosWrappers::MPI::Vector difference(a);
    difference -= b;
    return difference.linfty_norm();
  }



  // A vector with entries of every magnitude and sign, so that the rows'
  // sums round.
  TrilinosWrappers::MPI::Vector
  test_vector(const TrilinosWrappers::MPI::Vector &like)
  {
    TrilinosWrappers::MPI::Vector v(like);
    for (const auto i : v.locally_owned_elements())
      v(i) = std::sin(1.7 * i + 0.3) * std::exp(std::cos(0.37 * i));
    v.compress(VectorOperation::insert);
    return v;
  }



  void
  use_threads(const unsigned int n)
  {
    MultithreadInfo::set_thread_limit(n);
    AssertThrow(MultithreadInfo::n_threads() == n,
                ExcMessage("this test needs " + std::to_string(n) +
                           " threads: DEAL_II_NUM_THREADS limits them"));
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  // 5 refinements: 4,225 unknowns, so that the products' rows (2,048 per
  // task) and patches (256 per task) are shared among several tasks.
  testing::ReactionDiffusionSystem system =
    testing::reaction_diffusion_system(comm, 5);
  const TrilinosWrappers::MPI::Vector x = test_vector(system.b);
  out << "unknowns: " << system.A.m()
      << ", nonzero entries: " << system.A.n_nonzero_elements() << std::endl;

  // Epetra's product, one thread.
  TrilinosWrappers::MPI::Vector epetra(system.b), threaded(system.b);
  system.A.vmult(epetra, x);
  AssertThrow(epetra.linfty_norm() > 0, ExcInternalError());
  for (const unsigned int n_threads : {1u, 4u})
    {
      use_threads(n_threads);
      const ThreadedMatrixProduct product(system.A);
      // Else the comparison below would compare Epetra with itself.
      AssertThrow(product.threaded(),
                  ExcMessage("the matrix is multiplied by Epetra, not on "
                             "the threads"));
      threaded = 0;
      product.vmult(threaded, x);
      const double difference = largest_difference(threaded, epetra);
      out << n_threads
          << " thread(s): the threaded product equals Epetra's in every "
             "entry: "
          << (difference == 0 ? "yes" : "no") << std::endl;
      AssertThrow(difference == 0,
                  ExcMessage("threaded product differs from Epetra's by " +
                             std::to_string(difference)));
    }

  // The preconditioner and the truncated CG, with 1 and with 4 threads.
  std::array<TrilinosWrappers::MPI::Vector, 2> z, minimiser;
  std::array<TruncatedMinimisation, 2>         result;
  std::array<std::size_t, 2>                   n_patches;
  std::array<double, 2>                        mean_size;
  const double offset = 2 * (system.b * system.b);
  for (const unsigned int run : {0u, 1u})
    {
      use_threads(run == 0 ? 1 : 4);
      const AdditiveSchwarzPreconditioner stars(system.A,
                                                system.stars,
                                                system.relevant);
      n_patches[run] = stars.n_patches();
      mean_size[run] = stars.mean_patch_size();
      z[run].reinit(system.b);
      stars.vmult(z[run], x);
      minimiser[run].reinit(system.b);
      result[run] = minimise_by_truncated_cg(
        system.A, minimiser[run], system.b, stars, offset, 1e-6, 10, 2000);
    }
  use_threads(1);
  AssertThrow(z[0].linfty_norm() > 0 && minimiser[0].linfty_norm() > 0,
              ExcInternalError());
  const bool same_patches =
    n_patches[0] == n_patches[1] && mean_size[0] == mean_size[1];
  const bool same_preconditioned = largest_difference(z[0], z[1]) == 0;
  const bool same_minimisation =
    result[0].steps == result[1].steps && result[0].value == result[1].value &&
    largest_difference(minimiser[0], minimiser[1]) == 0;
  out << "additive Schwarz, 4 threads against 1: the same patches: "
      << (same_patches ? "yes" : "no") << ", P^-1 x the same in every entry: "
      << (same_preconditioned ? "yes" : "no") << std::endl
      << "truncated CG, 4 threads against 1: the same steps, J and "
         "minimiser in every entry: "
      << (same_minimisation ? "yes" : "no") << std::endl;
  AssertThrow(same_patches && same_preconditioned && same_minimisation,
              ExcMessage("the threaded preconditioner or CG depends on the "
                         "number of threads"));

  // The product on Epetra vectors: views of the vectors' owned entries,
  // as ReducedMatrix passes them.
  {
    use_threads(4);
    const Epetra_CrsMatrix     &matrix = system.A.trilinos_matrix();
    const ThreadedMatrixProduct product(matrix);
    AssertThrow(product.threaded(), ExcInternalError());
    threaded = 0;
    const Epetra_Vector x_view(View,
                               matrix.DomainMap(),
                               const_cast<double *>(x.begin()));
    Epetra_Vector       y_view(View, matrix.RangeMap(), threaded.begin());
    product.vmult(y_view, x_view);
    const double difference = largest_difference(threaded, epetra);
    out << "on Epetra vectors, 4 threads: the threaded product equals "
           "Epetra's in every entry: "
        << (difference == 0 ? "yes" : "no") << std::endl;
    AssertThrow(difference == 0,
                ExcMessage("threaded product on Epetra vectors differs from "
                           "Epetra's by " +
                           std::to_string(difference)));
  }

  // GMRES with 1 and 4 threads, on 6 refinements (16,641 unknowns): deal.II
  // shares vector operations among threads only above a few thousand
  // entries per rank.
  const testing::ReactionDiffusionSystem larger =
    testing::reaction_diffusion_system(comm, 6);
  parameters::LinearSolver settings;
  settings.relative_tolerance = 1e-10;
  settings.max_iterations     = 1000;
  TrilinosWrappers::PreconditionAMG amg;
  amg.initialize(larger.A);
  // Runs with 1, 4 and again 4 threads.
  std::array<TrilinosWrappers::MPI::Vector, 3> gmres_solution;
  std::array<LinearSolverReport, 3>            gmres_report;
  std::array<double, 3>                        relative_residual;
  for (const unsigned int run : {0u, 1u, 2u})
    {
      use_threads(run == 0 ? 1 : 4);
      gmres_solution[run].reinit(larger.b);
      gmres_report[run] = solve_krylov(larger.A,
                                       gmres_solution[run],
                                       larger.b,
                                       amg,
                                       settings,
                                       /*symmetric=*/false);
      TrilinosWrappers::MPI::Vector residual(larger.b);
      larger.A.vmult(residual, gmres_solution[run]);
      residual -= larger.b;
      relative_residual[run] = residual.l2_norm() / larger.b.l2_norm();
    }
  use_threads(1);
  AssertThrow(gmres_report[0].method == "gmres+amg" &&
                gmres_report[0].n_iterations > 3,
              ExcMessage("GMRES did not run: " + gmres_report[0].method + ", " +
                         std::to_string(gmres_report[0].n_iterations) +
                         " steps"));
  const bool residuals_below_tolerance =
    *std::max_element(relative_residual.begin(), relative_residual.end()) <=
    settings.relative_tolerance;
  const bool reproducible =
    gmres_report[1].n_iterations == gmres_report[2].n_iterations &&
    largest_difference(gmres_solution[1], gmres_solution[2]) == 0;
  const double threads_difference =
    largest_difference(gmres_solution[0], gmres_solution[1]) /
    gmres_solution[0].linfty_norm();
  out << "GMRES + AMG: |b - A x| / |b| below 1e-10 with 1 and 4 threads: "
      << (residuals_below_tolerance ? "yes" : "no")
      << "; 4 threads twice: the same steps and solution in every entry: "
      << (reproducible ? "yes" : "no")
      << "; 4 threads against 1: solutions within 1e-12 (relative): "
      << (threads_difference <= 1e-12 ? "yes" : "no") << std::endl;
  AssertThrow(
    residuals_below_tolerance && reproducible && threads_difference <= 1e-12,
    ExcMessage(
      "GMRES: residuals " + std::to_string(relative_residual[0]) + ", " +
      std::to_string(relative_residual[1]) +
      "; 4 threads twice reproducible: " + std::to_string(reproducible) +
      "; 4 threads against 1 differ by " + std::to_string(threads_difference)));
}
