#ifndef coulomb_adapt_app_single_process_messaging_h
#define coulomb_adapt_app_single_process_messaging_h

namespace coulomb_adapt
{
  /**
   * Before MPI_Init: a process started without a launcher (a plain
   * `coulomb-adapt`, a one-rank run) asks Open MPI for its shared-memory
   * messaging layer (`pml` ob1) instead of letting Open MPI probe the
   * network layers (UCX, libfabric) that a single process never uses.
   * Probing them takes about 0.2 s of every run's start (MPI_Init 0.27 s
   * against 0.07 s on Debian 12's Open MPI 4.1; benchmarks/adaptive_run).
   *
   * Nothing changes when the user chose a `pml` (OMPI_MCA_pml set), nor
   * for a process started by a launcher (mpirun, srun: their environment
   * names the rank), whose messaging is the cluster's choice. Other MPI
   * implementations ignore the variable.
   *
   * Returns whether the choice was made.
   */
  bool
  prefer_shared_memory_messaging_for_single_process();
} // namespace coulomb_adapt

#endif
