#ifndef coulomb_adapt_app_one_node_messaging_h
#define coulomb_adapt_app_one_node_messaging_h

namespace coulomb_adapt
{
  /**
   * Before MPI_Init: when every rank runs on one node, start Open MPI
   * without the work that only a cluster needs.
   *
   * - A process started without a launcher (a plain `coulomb-adapt`):
   *   `pml` ob1, Open MPI's shared-memory messaging, instead of probing
   *   the network layers a single process never uses; and
   *   `ess_singleton_isolated`, no `orted` daemon forked for it (a run
   *   spawns no processes and connects to none).
   * - Ranks started by Open MPI's mpirun all on this node
   *   (OMPI_COMM_WORLD_LOCAL_SIZE = OMPI_COMM_WORLD_SIZE): `pml` ob1. Its
   *   shared-memory transport is what carries the messages between ranks
   *   of one node; otherwise every rank probes the PSM/PSM2 layers of
   *   Omni-Path and InfiniPath hardware first, about 0.1 s each when the
   *   node has none.
   *
   * What it saves at every start (Debian 12's Open MPI 4.1, this
   * 2-core machine, `prm/blocks.prm`, whole runs of 0.3-1.3 s; numbers in
   * benchmarks/adaptive_run/README.md): 0.05-0.1 s on 1 rank, where the
   * daemon was forked (the choice of ob1 alone saved 0.2 s before), and
   * 0.20-0.26 s on 2 ranks.
   *
   * Nothing changes for a variable the user set (OMPI_MCA_pml,
   * OMPI_MCA_ess_singleton_isolated, also through `mpirun --mca`), for
   * ranks on several nodes, and for other launchers (srun, PMIx's or
   * PMI's): their messaging is the cluster's choice. A choice made only
   * in Open MPI's parameter files (`pml = ...` in
   * /etc/openmpi/openmpi-mca-params.conf or ~/.openmpi/mca-params.conf)
   * is overridden on one node: the environment takes precedence over
   * them (Debian's file only excludes ucx, which ob1 respects). Other
   * MPI implementations ignore the variables.
   *
   * Returns whether anything was chosen.
   */
  bool
  prefer_shared_memory_messaging_on_one_node();
} // namespace coulomb_adapt

#endif
