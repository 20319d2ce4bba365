#include <coulomb_adapt/app/one_node_messaging.h>

#include <array>
#include <cstdlib>
#include <string>

namespace coulomb_adapt
{
  namespace
  {
    // Set @p name to @p value unless the user set it; whether it was set.
    bool
    choose_unless_set(const char *name, const char *value)
    {
      if (std::getenv(name) != nullptr)
        return false;
      return setenv(name, value, /*overwrite=*/0) == 0;
    }



    bool
    is_set(const char *name)
    {
      return std::getenv(name) != nullptr;
    }
  } // namespace



  bool
  prefer_shared_memory_messaging_on_one_node()
  {
    // Open MPI's mpirun names the ranks of the job and those on this node.
    if (is_set("OMPI_COMM_WORLD_SIZE"))
      {
        const char *local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
        if (local == nullptr ||
            std::string(local) != std::getenv("OMPI_COMM_WORLD_SIZE"))
          return false;
        return choose_unless_set("OMPI_MCA_pml", "ob1");
      }
    // Set by PMIx launchers (srun, prterun), by PMI-1/2 launchers (MPICH's
    // hydra, srun) and by Slurm for every rank.
    const std::array<const char *, 4> other_launchers = {
      {"PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"}};
    for (const char *name : other_launchers)
      if (is_set(name))
        return false;
    const bool pml = choose_unless_set("OMPI_MCA_pml", "ob1");
    const bool isolated =
      choose_unless_set("OMPI_MCA_ess_singleton_isolated", "1");
    return pml || isolated;
  }
} // namespace coulomb_adapt
