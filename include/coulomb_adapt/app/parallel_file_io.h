#ifndef coulomb_adapt_app_parallel_file_io_h
#define coulomb_adapt_app_parallel_file_io_h

namespace coulomb_adapt
{
  /**
   * Before MPI_Init: ask Open MPI for its ROMIO implementation of MPI-IO
   * instead of OMPIO (OMPI_MCA_io=^ompio: any ROMIO it was built with,
   * romio321 in Open MPI 4.1, romio341 in 5.0), for the parallel HDF5
   * files (`Output/Format = hdf5`).
   *
   * Why: Open MPI 4.1's OMPIO opens every file with a shared-file-pointer
   * component, on one node its `sm` one, which creates a POSIX named
   * semaphore /dev/shm/sem.OMPIO_<file name without its directory> and
   * removes it at MPI_File_close. A run killed while it writes an .h5
   * file (a node failure, a job limit, Ctrl-C on mpirun) can leave that
   * semaphore locked, and every later run on the machine that writes a
   * file of the same name (body-1_000.h5.tmp: any run's first cycle)
   * waits on it forever; two runs writing the same name at the same time
   * in different directories share it. The HDF5 writer never uses a
   * shared file pointer. ROMIO creates no semaphore and no auxiliary
   * file, and wrote the same files in the same time (benchmarks/
   * adaptive_run, 2 ranks, blocks at epsilon_0 = 0.25 %: output 1.11-1.13 s
   * against OMPIO's 1.13-1.17 s).
   *
   * Nothing changes when the user chose an implementation (OMPI_MCA_io
   * set, also by `mpirun --mca io ...`, e.g. for a parallel file system
   * OMPIO is tuned for). A choice in Open MPI's parameter files only is
   * overridden: the environment takes precedence over them. Other MPI
   * implementations ignore the variable. Returns whether the choice was
   * made.
   */
  bool
  prefer_mpi_io_without_named_semaphores();
} // namespace coulomb_adapt

#endif
