// minimise_by_truncated_cg with the AdditiveSchwarzPreconditioner
// (solvers/truncated_minimisation.h,
// solvers/additive_schwarz_preconditioner.h), how the CRE estimator minimises
// its relaxed parameters' system
// ('CRE minimisation tolerance' > 0). On the SPD system of a P2
// reaction-diffusion problem on a distributed mesh (split between the
// ranks of a 2-rank run), with the patches the estimator uses (the
// unknowns of the cells around each vertex), and J(x) = offset + x.A x -
// 2 b.x whose minimum J* = offset - b.x* comes from the direct solve
// (solve_symmetric_positive_definite):
//
// - one patch holding every unknown makes the preconditioner A^-1: CG
//   reaches x* in its first step (to 1e-10) and stops at the second;
// - with the vertex stars, J(x) is never below J*, the stopping test
//   (the last 10 steps lowered J by less than tol J) leaves J within
//   10 tol of J* for tol = 1e-4 and 1e-8, and the J the iteration reports
//   is J(x) recomputed from x; the stars need fewer steps than point
//   Jacobi (singleton patches);
// - homogeneity: b * 1000 and offset * 1e6 give x * 1000 to 1e-12 and the
//   same number of steps;
// - an unknown whose row and column are zero (a name without a
//   parameter, then given a unit diagonal as the estimator does) is
//   dropped from the patches and stays 0.
//
// The 2-rank run prints what the 1-rank run prints.

#include <coulomb_adapt/solvers/additive_schwarz_preconditioner.h>
#include <coulomb_adapt/solvers/symmetric_direct_solver.h>
#include <coulomb_adapt/solvers/truncated_minimisation.h>

#include "reaction_diffusion_system.h"
#include "test_utilities.h"

#include <cmath>

using namespace coulomb_adapt;

namespace
{
  using Patches = std::vector<std::vector<types::global_dof_index>>;
  using testing::ReactionDiffusionSystem;
  using testing::relative_difference;

  // J(x) = offset + x.A x - 2 b.x, recomputed from x.
  double
  objective(const ReactionDiffusionSystem       &system,
            const TrilinosWrappers::MPI::Vector &x,
            const double                         offset)
  {
    TrilinosWrappers::MPI::Vector Ax(system.b);
    system.A.vmult(Ax, x);
    return offset + x * Ax - 2 * (system.b * x);
  }



} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  ReactionDiffusionSystem system = testing::reaction_diffusion_system(comm);
  // The other patchings: per owned unknown itself (point Jacobi), and
  // every unknown in one patch on rank 0 (then the preconditioner is A^-1).
  Patches singletons, everything;
  for (const auto i : system.A.locally_owned_range_indices())
    singletons.push_back({i});
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    {
      everything.emplace_back();
      complete_index_set(system.A.m()).fill_index_vector(everything.back());
    }
  TrilinosWrappers::MPI::Vector x_star(system.b), x(system.b);
  solve_symmetric_positive_definite(system.A, x_star, system.b);
  // J* = b.x* > 0, like an estimate.
  const double offset = 2 * (system.b * x_star);
  const double J_star = offset - system.b * x_star;
  out << "unknowns: " << system.A.m() << std::endl;

  // The relevant set of the last patch family must hold every index.
  const IndexSet all = complete_index_set(system.A.m());
  {
    const AdditiveSchwarzPreconditioner exact(system.A, everything, all);
    const auto                          result = minimise_by_truncated_cg(
      system.A, x, system.b, exact, offset, 1e-8, 1, 50);
    // The first step reaches x*; the second finds nothing left to gain,
    // which is what the stopping test (window 1) waits for.
    out << "one patch of every unknown: at most 2 steps: "
        << (result.steps <= 2 ? "yes" : "no") << ", x = x* to 1e-10: "
        << (relative_difference(x, x_star) < 1e-10 ? "yes" : "no") << std::endl;
  }

  const AdditiveSchwarzPreconditioner stars(system.A,
                                            system.stars,
                                            system.relevant);
  const AdditiveSchwarzPreconditioner jacobi(system.A,
                                             singletons,
                                             system.relevant);
  out << "vertex stars: " << stars.n_patches() << " patches, mean size "
      << std::round(stars.mean_patch_size()) << std::endl;
  for (const double tolerance : {1e-4, 1e-8})
    {
      const auto star_result = minimise_by_truncated_cg(
        system.A, x, system.b, stars, offset, tolerance, 10, 2000);
      const double J     = objective(system, x, offset);
      const double gap   = (J - J_star) / J_star;
      const auto   point = minimise_by_truncated_cg(
        system.A, x, system.b, jacobi, offset, tolerance, 10, 2000);
      out << "tolerance " << tolerance
          << ": J >= J*: " << (gap >= -1e-14 ? "yes" : "no")
          << ", J - J* <= 10 tol J*: " << (gap <= 10 * tolerance ? "yes" : "no")
          << ", reported J = J(x) to 1e-12: "
          << (std::abs(star_result.value - J) <= 1e-12 * J ? "yes" : "no")
          << ", stopped by the test: " << (star_result.converged ? "yes" : "no")
          << ", fewer steps than point Jacobi: "
          << (star_result.steps < point.steps ? "yes" : "no") << std::endl;
    }

  TrilinosWrappers::MPI::Vector b_scaled(system.b), x_scaled(system.b);
  b_scaled *= 1000.;
  const auto unscaled = minimise_by_truncated_cg(
    system.A, x, system.b, stars, offset, 1e-4, 10, 2000);
  const auto scaled = minimise_by_truncated_cg(
    system.A, x_scaled, b_scaled, stars, 1e6 * offset, 1e-4, 10, 2000);
  x_scaled /= 1000.;
  out << "b * 1000, offset * 1e6: x * 1000 to 1e-12: "
      << (relative_difference(x_scaled, x) < 1e-12 ? "yes" : "no")
      << ", the same steps: " << (scaled.steps == unscaled.steps ? "yes" : "no")
      << std::endl;

  // A name without a parameter: the first row and column zero when the
  // preconditioner is built, then a unit diagonal and no load.
  const types::global_dof_index first = 0;
  if (system.A.in_local_range(first))
    for (auto entry = system.A.begin(first); entry != system.A.end(first);
         ++entry)
      entry->value() = 0;
  for (const auto i : system.A.locally_owned_range_indices())
    if (system.A.el(i, first) != 0)
      system.A.set(i, first, 0.);
  system.A.compress(VectorOperation::insert);
  const AdditiveSchwarzPreconditioner without_first(system.A,
                                                    system.stars,
                                                    system.relevant);
  if (system.A.in_local_range(first))
    {
      system.A.set(first, first, 1.);
      system.b(first) = 0;
    }
  system.A.compress(VectorOperation::insert);
  system.b.compress(VectorOperation::insert);
  minimise_by_truncated_cg(
    system.A, x, system.b, without_first, offset, 1e-8, 10, 2000);
  const double first_value =
    Utilities::MPI::sum(system.A.in_local_range(first) ? x(first) : 0., comm);
  out << "an unknown with a zero row stays 0: "
      << (first_value == 0 ? "yes" : "no") << std::endl;
}
