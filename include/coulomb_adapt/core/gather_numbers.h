#ifndef coulomb_adapt_core_gather_numbers_h
#define coulomb_adapt_core_gather_numbers_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <vector>

namespace coulomb_adapt
{
  /**
   * Every rank's @p local doubles, on rank @p root (one vector per rank, in
   * rank order; empty on the other ranks).
   *
   * Utilities::MPI::gather() of deal.II 9.4 serialises the vectors through
   * boost: for the size field of a remeshed body (8 numbers per cell) that
   * took 0.1 s of an adaptive run on one rank. Plain doubles need no
   * serialisation: MPI_Gatherv.
   */
  inline std::vector<std::vector<double>>
  gather_numbers(const MPI_Comm             comm,
                 const std::vector<double> &local,
                 const unsigned int         root)
  {
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
    const bool is_root = dealii::Utilities::MPI::this_mpi_process(comm) == root;
    const int  n_local = static_cast<int>(local.size());
    std::vector<int> counts(is_root ? n_ranks : 0);
    int              ierr =
      MPI_Gather(&n_local, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm);
    AssertThrowMPI(ierr);
    std::vector<int> starts(counts.size(), 0);
    for (unsigned int r = 1; r < counts.size(); ++r)
      starts[r] = starts[r - 1] + counts[r - 1];
    std::vector<double> all(is_root ? starts.back() + counts.back() : 0);
    ierr = MPI_Gatherv(local.data(),
                       n_local,
                       MPI_DOUBLE,
                       all.data(),
                       counts.data(),
                       starts.data(),
                       MPI_DOUBLE,
                       root,
                       comm);
    AssertThrowMPI(ierr);
    std::vector<std::vector<double>> parts(counts.size());
    for (unsigned int r = 0; r < counts.size(); ++r)
      parts[r].assign(all.begin() + starts[r],
                      all.begin() + starts[r] + counts[r]);
    return parts;
  }
} // namespace coulomb_adapt

#endif
