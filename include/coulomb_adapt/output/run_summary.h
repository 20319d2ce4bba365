#ifndef coulomb_adapt_output_run_summary_h
#define coulomb_adapt_output_run_summary_h

#include <deal.II/base/mpi.h>

#include <nlohmann/json.hpp>

#include <string>

namespace coulomb_adapt
{
  /**
   * The machine-readable record of a run, `summary.json` in the output
   * directory: the run's identity and one entry per cycle. It is rewritten
   * (atomically, by rank 0) after every cycle, so an interrupted run keeps
   * the cycles it finished. Keys are only ever added, never renamed.
   */
  class RunSummary
  {
  public:
    RunSummary(const MPI_Comm     mpi_communicator,
               const std::string &file_name,
               const std::string &scene,
               const std::string &parameter_file);

    /** Set a top-level entry and rewrite the file. */
    void
    set(const std::string &key, const nlohmann::json &value);

    /** Append a cycle's record and rewrite the file. */
    void
    add_cycle(const nlohmann::json &cycle);

    const nlohmann::json &
    data() const;

  private:
    void
    write() const;

    const MPI_Comm    mpi_communicator;
    const std::string file_name;
    nlohmann::json    summary;
  };
} // namespace coulomb_adapt

#endif
