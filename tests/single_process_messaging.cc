// prefer_shared_memory_messaging_for_single_process (app/single_process_
// messaging.h), before MPI_Init as in main():
//  - a process with no launcher variable and no OMPI_MCA_pml gets
//    OMPI_MCA_pml=ob1 and true;
//  - OMPI_MCA_pml chosen by the user (cm) stays, false;
//  - each launcher variable alone (mpirun's OMPI_COMM_WORLD_SIZE, PMIx's
//    PMIX_RANK, PMI's PMI_RANK / PMI_SIZE, Slurm's SLURM_PROCID) leaves
//    OMPI_MCA_pml unset, false;
//  - as this test was started: chosen without a launcher and without the
//    user's OMPI_MCA_pml (ctest starts the 1-rank variant alone), not
//    under mpirun (2 ranks); then MPI starts with that choice and a sum
//    over the ranks is right.
// The launcher's own variables are restored before MPI_Init.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/single_process_messaging.h>

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
  const std::vector<std::string> launcher_variables = {"OMPI_COMM_WORLD_SIZE",
                                                       "PMIX_RANK",
                                                       "PMI_RANK",
                                                       "PMI_SIZE",
                                                       "SLURM_PROCID"};

  std::optional<std::string>
  get(const std::string &name)
  {
    const char *value = std::getenv(name.c_str());
    return value ? std::optional<std::string>(value) : std::nullopt;
  }

  void
  set(const std::string &name, const std::optional<std::string> &value)
  {
    if (value)
      setenv(name.c_str(), value->c_str(), 1);
    else
      unsetenv(name.c_str());
  }

  std::string
  describe(const bool chosen)
  {
    const auto pml = get("OMPI_MCA_pml");
    return std::string(chosen ? "chosen" : "not chosen") +
           ", OMPI_MCA_pml = " + (pml ? *pml : std::string("(unset)"));
  }
} // namespace

int
main(int argc, char *argv[])
{
  std::map<std::string, std::optional<std::string>> as_started;
  for (const std::string &name : launcher_variables)
    as_started[name] = get(name);
  as_started["OMPI_MCA_pml"] = get("OMPI_MCA_pml");
  // Any launcher's variable, not only mpirun's: ctest may run inside a
  // Slurm allocation, or with the user's own OMPI_MCA_pml.
  bool launched = false;
  for (const std::string &name : launcher_variables)
    launched = launched || as_started[name].has_value();
  const bool user_pml = as_started["OMPI_MCA_pml"].has_value();

  std::ostringstream log;
  bool               all_right = true;
  auto               check     = [&](const std::string                &what,
                   const bool                        chosen,
                   const bool                        expected_chosen,
                   const std::optional<std::string> &expected_pml) {
    const bool right =
      chosen == expected_chosen && get("OMPI_MCA_pml") == expected_pml;
    all_right = all_right && right;
    log << what << ": " << describe(chosen) << (right ? "" : "  WRONG") << "\n";
  };

  // No launcher, nothing chosen.
  for (const std::string &name : launcher_variables)
    unsetenv(name.c_str());
  unsetenv("OMPI_MCA_pml");
  check("no launcher",
        prefer_shared_memory_messaging_for_single_process(),
        true,
        std::string("ob1"));

  // The user's choice stays.
  setenv("OMPI_MCA_pml", "cm", 1);
  check("no launcher, OMPI_MCA_pml=cm",
        prefer_shared_memory_messaging_for_single_process(),
        false,
        std::string("cm"));

  for (const std::string &name : launcher_variables)
    {
      unsetenv("OMPI_MCA_pml");
      setenv(name.c_str(), "0", 1);
      check(name + " set",
            prefer_shared_memory_messaging_for_single_process(),
            false,
            std::nullopt);
      unsetenv(name.c_str());
    }

  // As started: restore the launcher's environment, then choose as main()
  // does, and start MPI with it.
  for (const auto &[name, value] : as_started)
    set(name, value);
  const bool chosen = prefer_shared_memory_messaging_for_single_process();
  const bool expected_chosen = !launched && !user_pml;
  const std::optional<std::string> expected_pml =
    expected_chosen ? std::string("ob1") : as_started["OMPI_MCA_pml"];
  const bool as_expected =
    chosen == expected_chosen && get("OMPI_MCA_pml") == expected_pml;
  all_right = all_right && as_expected;
  // Printed without the values, which depend on how ctest was started.
  log << "as started (" << (launched ? "with" : "without") << " a launcher): "
      << (as_expected ? std::string("as expected") :
                        "WRONG: " + describe(chosen))
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
