#include <coulomb_adapt/solvers/threaded_matrix_product.h>
#include <coulomb_adapt/solvers/truncated_minimisation.h>

#include <deque>
#include <numeric>

namespace coulomb_adapt
{
  TruncatedMinimisation
  minimise_by_truncated_cg(const TrilinosWrappers::SparseMatrix &A,
                           TrilinosWrappers::MPI::Vector        &x,
                           const TrilinosWrappers::MPI::Vector  &b,
                           const AdditiveSchwarzPreconditioner  &P,
                           const double                          offset,
                           const double       relative_tolerance,
                           const unsigned int window,
                           const unsigned int max_steps)
  {
    TruncatedMinimisation result;
    result.value = offset;
    x            = 0;
    const ThreadedMatrixProduct   product(A);
    TrilinosWrappers::MPI::Vector r(b), z(b), p(b), Ap(b);
    P.vmult(z, r);
    p          = z;
    double r_z = r * z;
    // The decreases of the last `window` steps.
    std::deque<double> recent;
    while (result.steps < max_steps && r_z > 0)
      {
        product.vmult(Ap, p);
        const double a = r_z / (p * Ap);
        x.add(a, p);
        r.add(-a, Ap);
        ++result.steps;
        // J(x + a p) = J(x) - a r.z for the CG step length a.
        result.decrease += a * r_z;
        result.value = offset - result.decrease;
        recent.push_back(a * r_z);
        if (recent.size() > window)
          recent.pop_front();
        if (recent.size() == window &&
            std::accumulate(recent.begin(), recent.end(), 0.) <=
              relative_tolerance * result.value)
          {
            result.converged = true;
            break;
          }
        P.vmult(z, r);
        const double r_z_new = r * z;
        p.sadd(r_z_new / r_z, 1., z);
        r_z = r_z_new;
      }
    if (r_z <= 0)
      result.converged = true;
    return result;
  }
} // namespace coulomb_adapt
