// prefer_shared_memory_messaging_on_one_node (app/one_node_messaging.h),
// before MPI_Init as in main():
//  - no launcher variable: OMPI_MCA_pml=ob1 and
//    OMPI_MCA_ess_singleton_isolated=1, true; a variable the user set
//    (pml cm, isolated 0) stays, the other one is still chosen;
//  - mpirun's ranks all on this node (OMPI_COMM_WORLD_LOCAL_SIZE =
//    OMPI_COMM_WORLD_SIZE): OMPI_MCA_pml=ob1, no singleton variable;
//    the user's pml stays;
//  - mpirun's ranks on several nodes (local size 2 of 4), or without the
//    local size: nothing chosen;
//  - each other launcher variable alone (PMIx's PMIX_RANK, PMI's
//    PMI_RANK / PMI_SIZE, Slurm's SLURM_PROCID): nothing chosen;
//  - as this test was started (ctest: 1 rank without a launcher, 2 ranks
//    under mpirun on this machine): the choice the rules above give; then
//    MPI starts with it and a sum over the ranks is right.
// The environment as started is restored before MPI_Init.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/one_node_messaging.h>

#include "test_utilities.h"

#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace coulomb_adapt;

namespace
{
  const std::vector<std::string> variables = {
    "OMPI_COMM_WORLD_SIZE",
    "OMPI_COMM_WORLD_LOCAL_SIZE",
    "PMIX_RANK",
    "PMI_RANK",
    "PMI_SIZE",
    "SLURM_PROCID",
    "OMPI_MCA_pml",
    "OMPI_MCA_ess_singleton_isolated"};

  using Environment = std::map<std::string, std::optional<std::string>>;

  std::optional<std::string>
  get(const std::string &name)
  {
    const char *value = std::getenv(name.c_str());
    return value ? std::optional<std::string>(value) : std::nullopt;
  }

  // Exactly @p environment for the variables above.
  void
  set(const Environment &environment)
  {
    for (const std::string &name : variables)
      {
        const auto it = environment.find(name);
        if (it != environment.end() && it->second)
          setenv(name.c_str(), it->second->c_str(), 1);
        else
          unsetenv(name.c_str());
      }
  }

  std::string
  value_of(const std::string &name)
  {
    const auto value = get(name);
    return value ? *value : std::string("(unset)");
  }
} // namespace

int
main(int argc, char *argv[])
{
  Environment as_started;
  for (const std::string &name : variables)
    as_started[name] = get(name);

  std::ostringstream log;
  bool               all_right = true;
  // Start from @p before, choose, and compare with the expected choice and
  // the expected values of the two variables.
  auto check = [&](const std::string                &what,
                   const Environment                &before,
                   const bool                        expected_chosen,
                   const std::optional<std::string> &expected_pml,
                   const std::optional<std::string> &expected_isolated) {
    set(before);
    const bool chosen = prefer_shared_memory_messaging_on_one_node();
    const bool right =
      chosen == expected_chosen && get("OMPI_MCA_pml") == expected_pml &&
      get("OMPI_MCA_ess_singleton_isolated") == expected_isolated;
    all_right = all_right && right;
    log << what << ": " << (chosen ? "chosen" : "not chosen")
        << ", pml = " << value_of("OMPI_MCA_pml") << ", singleton isolated = "
        << value_of("OMPI_MCA_ess_singleton_isolated")
        << (right ? "" : "  WRONG") << "\n";
  };
  const std::optional<std::string> unset;

  check("no launcher", {}, true, "ob1", "1");
  check("no launcher, the user's pml cm",
        {{"OMPI_MCA_pml", "cm"}},
        true,
        "cm",
        "1");
  check("no launcher, the user's isolated 0",
        {{"OMPI_MCA_ess_singleton_isolated", "0"}},
        true,
        "ob1",
        "0");
  check("no launcher, both the user's",
        {{"OMPI_MCA_pml", "cm"}, {"OMPI_MCA_ess_singleton_isolated", "0"}},
        false,
        "cm",
        "0");
  check("mpirun, 2 of 2 ranks on this node",
        {{"OMPI_COMM_WORLD_SIZE", "2"},
         {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"},
         {"PMIX_RANK", "0"}},
        true,
        "ob1",
        unset);
  check("mpirun, 2 of 2 ranks on this node, the user's pml cm",
        {{"OMPI_COMM_WORLD_SIZE", "2"},
         {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"},
         {"OMPI_MCA_pml", "cm"}},
        false,
        "cm",
        unset);
  check("mpirun, 2 of 4 ranks on this node",
        {{"OMPI_COMM_WORLD_SIZE", "4"},
         {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"},
         {"PMIX_RANK", "0"}},
        false,
        unset,
        unset);
  check("mpirun without a local size",
        {{"OMPI_COMM_WORLD_SIZE", "2"}},
        false,
        unset,
        unset);
  for (const std::string name :
       {"PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
    check(name + " alone", {{name, "0"}}, false, unset, unset);

  // As started: the rules above applied to the environment ctest gave.
  const bool mpirun         = as_started["OMPI_COMM_WORLD_SIZE"].has_value();
  bool       other_launcher = false;
  for (const std::string name :
       {"PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
    other_launcher = other_launcher || as_started[name].has_value();
  const bool one_node = mpirun && as_started["OMPI_COMM_WORLD_LOCAL_SIZE"] ==
                                    as_started["OMPI_COMM_WORLD_SIZE"];
  const bool                       no_launcher = !mpirun && !other_launcher;
  const std::optional<std::string> expected_pml =
    (one_node || no_launcher) && !as_started["OMPI_MCA_pml"] ?
      std::string("ob1") :
      as_started["OMPI_MCA_pml"];
  const std::optional<std::string> expected_isolated =
    no_launcher && !as_started["OMPI_MCA_ess_singleton_isolated"] ?
      std::string("1") :
      as_started["OMPI_MCA_ess_singleton_isolated"];
  set(as_started);
  prefer_shared_memory_messaging_on_one_node();
  const bool as_expected =
    get("OMPI_MCA_pml") == expected_pml &&
    get("OMPI_MCA_ess_singleton_isolated") == expected_isolated;
  all_right = all_right && as_expected;
  // Printed without the values, which depend on how ctest was started.
  log << "as started ("
      << (one_node       ? "mpirun, one node" :
          mpirun         ? "mpirun, several nodes" :
          other_launcher ? "another launcher" :
                           "no launcher")
      << "): "
      << (as_expected ? std::string("as expected") :
                        "WRONG: pml = " + value_of("OMPI_MCA_pml") +
                          ", singleton isolated = " +
                          value_of("OMPI_MCA_ess_singleton_isolated"))
      << "\n";

  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const unsigned int sum =
    Utilities::MPI::sum(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) + 1,
                        MPI_COMM_WORLD);
  out << log.str();
  out << "MPI started on " << n_ranks << " rank(s); sum of rank + 1 = " << sum
      << (sum == n_ranks * (n_ranks + 1) / 2 ? "" : "  WRONG") << std::endl;
  AssertThrow(all_right && sum == n_ranks * (n_ranks + 1) / 2,
              ExcMessage("the messaging choice is wrong"));
  return 0;
}
