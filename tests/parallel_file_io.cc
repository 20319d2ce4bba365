// prefer_mpi_io_without_named_semaphores (app/parallel_file_io.h), before
// MPI_Init as in main():
//  - without OMPI_MCA_io it sets OMPI_MCA_io=^ompio and returns true;
//  - a user's OMPI_MCA_io (ompio, for a parallel file system) stays, false.
// Then MPI starts with the choice, opens a file through MPI-IO on every
// rank, writes one number per rank, and each rank reads back the others'
// (an MPI-IO component other than OMPIO exists in this Open MPI: else
// the open fails).
// The end-to-end check (a run beside a locked OMPIO semaphore) is
// bad_input.stale_io_semaphore.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/parallel_file_io.h>

#include "test_utilities.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

using namespace coulomb_adapt;

namespace
{
  std::string
  io_variable()
  {
    const char *value = std::getenv("OMPI_MCA_io");
    return value ? std::string(value) : std::string("(unset)");
  }
} // namespace

int
main(int argc, char *argv[])
{
  std::ostringstream log;
  bool               all_right = true;

  unsetenv("OMPI_MCA_io");
  setenv("OMPI_MCA_io", "ompio", 1);
  const bool user_choice_replaced = prefer_mpi_io_without_named_semaphores();
  log << "with the user's OMPI_MCA_io: "
      << (user_choice_replaced ? "chosen" : "not chosen")
      << ", OMPI_MCA_io = " << io_variable() << std::endl;
  all_right = all_right && !user_choice_replaced && io_variable() == "ompio";

  unsetenv("OMPI_MCA_io");
  const bool chosen = prefer_mpi_io_without_named_semaphores();
  log << "without it: " << (chosen ? "chosen" : "not chosen")
      << ", OMPI_MCA_io = " << io_variable() << std::endl;
  all_right = all_right && chosen && io_variable() == "^ompio";

  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
  auto               out     = testing::root_output();
  out << log.str();

  const std::string name =
    "parallel_file_io." + std::to_string(n_ranks) + ".bin";
  MPI_File file;
  int      error = MPI_File_open(
    comm, name.c_str(), MPI_MODE_CREATE | MPI_MODE_RDWR, MPI_INFO_NULL, &file);
  AssertThrow(error == MPI_SUCCESS,
              ExcMessage("MPI_File_open failed with OMPI_MCA_io = " +
                         io_variable()));
  const double mine = 1.5 + rank;
  error             = MPI_File_write_at_all(
    file, rank * sizeof(double), &mine, 1, MPI_DOUBLE, MPI_STATUS_IGNORE);
  AssertThrow(error == MPI_SUCCESS, ExcMessage("MPI_File_write_at_all"));
  MPI_File_sync(file);
  MPI_Barrier(comm);
  bool read_back = true;
  for (unsigned int r = 0; r < n_ranks; ++r)
    {
      double value = 0;
      MPI_File_read_at(
        file, r * sizeof(double), &value, 1, MPI_DOUBLE, MPI_STATUS_IGNORE);
      read_back = read_back && value == 1.5 + r;
    }
  MPI_File_close(&file);
  read_back = Utilities::MPI::min(read_back ? 1 : 0, comm) == 1;
  out << "MPI-IO on " << n_ranks << " rank(s): each rank read back every "
      << "rank's number: " << (read_back ? "yes" : "no") << std::endl;
  if (rank == 0)
    std::filesystem::remove(name);

  AssertThrow(all_right && read_back,
              ExcMessage("the choice of MPI-IO is not as documented"));
  return 0;
}
