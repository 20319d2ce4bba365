#include <coulomb_adapt/app/parallel_file_io.h>

#include <cstdlib>

namespace coulomb_adapt
{
  bool
  prefer_mpi_io_without_named_semaphores()
  {
    if (std::getenv("OMPI_MCA_io") != nullptr)
      return false;
    return setenv("OMPI_MCA_io", "^ompio", /*overwrite=*/0) == 0;
  }
} // namespace coulomb_adapt
