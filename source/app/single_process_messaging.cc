#include <coulomb_adapt/app/single_process_messaging.h>

#include <array>
#include <cstdlib>

namespace coulomb_adapt
{
  bool
  prefer_shared_memory_messaging_for_single_process()
  {
    // Set by Open MPI's mpirun, by PMIx launchers (srun, prterun), by
    // PMI-1/2 launchers (MPICH's hydra, srun) and by Slurm for every rank.
    const std::array<const char *, 5> launcher_variables = {
      {"OMPI_COMM_WORLD_SIZE",
       "PMIX_RANK",
       "PMI_RANK",
       "PMI_SIZE",
       "SLURM_PROCID"}};
    for (const char *name : launcher_variables)
      if (std::getenv(name) != nullptr)
        return false;
    if (std::getenv("OMPI_MCA_pml") != nullptr)
      return false;
    return setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0) == 0;
  }
} // namespace coulomb_adapt
