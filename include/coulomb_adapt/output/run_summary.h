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

    /** The run stops on an error in cycle @p cycle: `status` "failed",
     * `error` the message, `failed_in_cycle`; the cycles already recorded
     * stay. Rank 0 rewrites the file without waiting for the others (they
     * may be failing elsewhere); a failure to write is returned, not
     * thrown, so that the run's own error is the one reported. */
    std::string
    record_failure(const unsigned int cycle, const std::string &message);

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
