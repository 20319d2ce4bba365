#include <deal.II/base/multithread_info.h>

#include <coulomb_adapt/core/version.h>
#include <coulomb_adapt/output/file_writer.h>
#include <coulomb_adapt/output/run_summary.h>

namespace coulomb_adapt
{
  RunSummary::RunSummary(const MPI_Comm     mpi_communicator,
                         const std::string &file_name,
                         const std::string &scene,
                         const std::string &parameter_file)
    : mpi_communicator(mpi_communicator)
    , file_name(file_name)
  {
    summary["program"]        = "coulomb-adapt";
    summary["version"]        = version();
    summary["scene"]          = scene;
    summary["parameter_file"] = parameter_file;
    summary["mpi_processes"] =
      dealii::Utilities::MPI::n_mpi_processes(mpi_communicator);
    summary["threads_per_process"] = dealii::MultithreadInfo::n_threads();
    summary["cycles"]              = nlohmann::json::array();
    write();
  }



  void
  RunSummary::set(const std::string &key, const nlohmann::json &value)
  {
    summary[key] = value;
    write();
  }



  void
  RunSummary::add_cycle(const nlohmann::json &cycle)
  {
    summary["cycles"].push_back(cycle);
    write();
  }



  std::string
  RunSummary::record_failure(const unsigned int cycle,
                             const std::string &message)
  {
    summary["status"]          = "failed";
    summary["error"]           = message;
    summary["failed_in_cycle"] = cycle;
    if (dealii::Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return "";
    return write_file_on_this_process(file_name, [this](std::ostream &out) {
      out << summary.dump(2) << '\n';
    });
  }



  const nlohmann::json &
  RunSummary::data() const
  {
    return summary;
  }



  void
  RunSummary::write() const
  {
    write_file(mpi_communicator, file_name, [this](std::ostream &out) {
      out << summary.dump(2) << '\n';
    });
  }
} // namespace coulomb_adapt
