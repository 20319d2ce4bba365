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
//   minimiser, bit for bit, as with 1 thread.
//
// The 2-rank run prints what the 1-rank run prints.

#include <deal.II/base/multithread_info.h>

#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>
#include <coulomb_adapt/solvers/threaded_matrix_product.h>
#include <coulomb_adapt/solvers/truncated_minimisation.h>

#include "reaction_diffusion_system.h"
#include "test_utilities.h"

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
}
