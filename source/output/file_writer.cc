#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/reference_cell.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/output/file_writer.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <regex>
#include <system_error>

namespace coulomb_adapt
{
  using namespace dealii;

  namespace
  {
    // The system's reason for the last failed call, as " (reason)".
    std::string
    system_reason(const int error_number)
    {
      return error_number == 0 ?
               std::string() :
               std::string(" (") + std::strerror(error_number) + ")";
    }



    // Write @p path + ".tmp" on this rank; an empty string, or what went
    // wrong, naming @p path. The temporary file is removed on failure.
    std::string
    write_temporary(const std::string                         &path,
                    const std::function<void(std::ostream &)> &write)
    {
      const std::string temporary = path + ".tmp";
      std::string       error;
      errno = 0;
      std::ofstream out(temporary);
      if (!out)
        error = "cannot open it for writing" + system_reason(errno);
      else
        {
          try
            {
              write(out);
            }
          catch (const std::exception &e)
            {
              // deal.II's writers report a failed stream as a generic
              // ExcIO: the system's reason is more useful.
              const int error_number = errno;
              error = "writing it failed" + (error_number != 0 ?
                                               system_reason(error_number) :
                                               ": " + user_message(e));
            }
          // A full disk shows at the latest when the buffer is flushed and
          // the file closed.
          if (error.empty())
            {
              errno = 0;
              out.flush();
              if (out)
                out.close();
              if (!out)
                error = "writing it failed" + system_reason(errno);
            }
        }
      if (!error.empty())
        {
          std::remove(temporary.c_str());
          return "output file '" + path + "': " + error;
        }
      return "";
    }



    std::string
    rename_temporary(const std::string &path)
    {
      const std::string temporary = path + ".tmp";
      errno                       = 0;
      if (std::rename(temporary.c_str(), path.c_str()) != 0)
        {
          const int error_number = errno;
          std::remove(temporary.c_str());
          return "output file '" + path + "': cannot replace it" +
                 system_reason(error_number);
        }
      return "";
    }



    // Collective: the first rank's error, the same on every rank.
    std::string
    first_error(const MPI_Comm comm, const std::string &error)
    {
      for (const std::string &e : Utilities::MPI::all_gather(comm, error))
        if (!e.empty())
          return e;
      return "";
    }
  } // namespace



  void
  write_file(const MPI_Comm                             comm,
             const std::string                         &path,
             const std::function<void(std::ostream &)> &write)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        error = write_temporary(path, write);
        if (error.empty())
          error = rename_temporary(path);
      }
    error = Utilities::MPI::broadcast(comm, error, 0);
    AssertThrow(error.empty(), ExcMessage(error));
  }



  std::string
  write_file_on_this_process(const std::string                         &path,
                             const std::function<void(std::ostream &)> &write)
  {
    std::string error = write_temporary(path, write);
    if (error.empty())
      error = rename_temporary(path);
    return error;
  }



  namespace
  {
    // This rank's pieces, each to its own NAME.tmp, on concurrent tasks
    // (deal.II's writer encodes and compresses one file on one thread):
    // the first failure's message, or "".
    std::string
    write_own_pieces(const VtuPieces                &pieces,
                     const std::vector<std::string> &paths,
                     const DataOutBase::VtkFlags    &flags)
    {
      std::vector<std::string> errors(paths.size());
      {
        Threads::TaskGroup<> tasks;
        for (unsigned int p = 0; p < paths.size(); ++p)
          tasks += Threads::new_task([&, p]() {
            errors[p] = write_temporary(paths[p], [&](std::ostream &out) {
              DataOutBase::write_vtu(pieces.patches[p],
                                     pieces.names,
                                     pieces.nonscalar_ranges,
                                     flags,
                                     out);
            });
          });
        tasks.join_all();
      }
      for (const std::string &e : errors)
        if (!e.empty())
          return e;
      return "";
    }
  } // namespace



  VtuRecordWrite::VtuRecordWrite(const MPI_Comm               comm,
                                 VtuPieces                  &&pieces_to_write,
                                 const DataOutBase::VtkFlags &flags,
                                 const std::string           &directory,
                                 const std::string           &base_name,
                                 const unsigned int           cycle,
                                 const bool                   in_background)
    : pieces(std::make_shared<const VtuPieces>(std::move(pieces_to_write)))
    , flags(flags)
    , directory(directory)
    , record_name(base_name + "_" + Utilities::int_to_string(cycle, 3) +
                  ".pvtu")
  {
    const unsigned int n_own_pieces = pieces->patches.size();
    AssertThrow(n_own_pieces > 0, ExcInternalError());
    // The pieces are numbered over all ranks, rank by rank: with one piece
    // per rank these are deal.II's names (DataOutInterface::
    // write_vtu_with_pvtu_record), so that a small run looks as before.
    const std::vector<unsigned int> pieces_per_rank =
      Utilities::MPI::all_gather(comm, n_own_pieces);
    unsigned int n_pieces = 0, first_own_piece = 0;
    for (unsigned int r = 0; r < pieces_per_rank.size(); ++r)
      {
        if (r == Utilities::MPI::this_mpi_process(comm))
          first_own_piece = n_pieces;
        n_pieces += pieces_per_rank[r];
      }
    const unsigned int n_digits =
      Utilities::needed_digits(n_pieces > 1 ? n_pieces - 1 : 0);
    const std::string stem =
      base_name + "_" + Utilities::int_to_string(cycle, 3);
    for (unsigned int p = 0; p < n_pieces; ++p)
      piece_names.push_back(stem + "." + Utilities::int_to_string(p, n_digits) +
                            ".vtu");
    for (unsigned int p = 0; p < n_own_pieces; ++p)
      own_paths.push_back(directory + "/" + piece_names[first_own_piece + p]);

    // The thread gets its own copies and the shared pieces: nothing of
    // this object, which may be gone before the thread has ended.
    // A thread that cannot be started (std::system_error, perhaps on one
    // rank only) must not end this rank's run: the pieces are then
    // written by finish(), in the foreground.
    const auto write = [pieces = pieces, paths = own_paths, flags = flags]() {
      return write_own_pieces(*pieces, paths, flags);
    };
    try
      {
        own_pieces_written =
          std::async(in_background ? std::launch::async : std::launch::deferred,
                     write);
      }
    catch (const std::system_error &)
      {
        own_pieces_written = std::async(std::launch::deferred, write);
      }
  }



  std::string
  VtuRecordWrite::wait_for_own_pieces()
  {
    if (!own_pieces_written.valid())
      return "";
    try
      {
        return own_pieces_written.get();
      }
    catch (const std::exception &e)
      {
        return "output file '" + own_paths.front() +
               "': writing it failed: " + user_message(e);
      }
  }



  VtuRecordWrite::~VtuRecordWrite()
  {
    if (finished)
      return;
    // A write not started (deferred) is not started now.
    if (own_pieces_written.valid() &&
        own_pieces_written.wait_for(std::chrono::seconds(0)) !=
          std::future_status::deferred)
      wait_for_own_pieces();
    for (const std::string &path : own_paths)
      std::remove((path + ".tmp").c_str());
  }



  // Every rank learns of any rank's failure; the pieces are renamed only
  // when all ranks have written theirs, and only then the record that
  // lists them is written.
  std::string
  VtuRecordWrite::finish(const MPI_Comm comm)
  {
    Assert(!finished, ExcInternalError());
    std::string error = first_error(comm, wait_for_own_pieces());
    finished          = true;
    if (!error.empty())
      {
        for (const std::string &path : own_paths)
          std::remove((path + ".tmp").c_str());
        AssertThrow(false, ExcMessage(error));
      }
    std::string own_error;
    for (const std::string &path : own_paths)
      if (own_error.empty())
        own_error = rename_temporary(path);
      else
        std::remove((path + ".tmp").c_str());
    error = first_error(comm, own_error);
    AssertThrow(error.empty(), ExcMessage(error));

    write_file(comm, directory + "/" + record_name, [&](std::ostream &out) {
      DataOutBase::write_pvtu_record(
        out, piece_names, pieces->names, pieces->nonscalar_ranges, flags);
    });
    return record_name;
  }



  void
  write_hdf5_file(const MPI_Comm                                  comm,
                  const std::string                              &path,
                  const std::function<void(const std::string &)> &write)
  {
    const std::string temporary = path + ".tmp";
    std::string       error;
    errno = 0;
    try
      {
        write(temporary);
      }
    catch (const std::exception &e)
      {
        // HDF5 reports a failed open as a generic error: the system's
        // reason, when there is one, is more useful.
        const int error_number = errno;
        error = "output file '" + path + "': writing it failed" +
                (error_number != 0 ? system_reason(error_number) :
                                     ": " + user_message(e));
      }
    error = first_error(comm, error);
    if (!error.empty())
      {
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          std::remove(temporary.c_str());
        AssertThrow(false, ExcMessage(error));
      }
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      error = rename_temporary(path);
    error = Utilities::MPI::broadcast(comm, error, 0);
    AssertThrow(error.empty(), ExcMessage(error));
  }



  XDMFEntry
  write_hdf5(const MPI_Comm                comm,
             const DataOutInterface<2, 2> &data_out,
             const std::string            &directory,
             const std::string            &file_name,
             const double                  time)
  {
    // Duplicate vertices are kept: the indicator and the material id are
    // cell data, which merging the cells' vertices would smear.
    DataOutBase::DataOutFilter filter(
      DataOutBase::DataOutFilterFlags(false, true));
    data_out.write_filtered_data(filter);
    // deal.II 9.4's parallel HDF5 writer crashes on a rank without cells
    // (3 ranks, a body of 2 cells: SIGSEGV in write_hdf5_parallel, found
    // by a walkthrough; deal.II fixed it after 9.4). Only the ranks with
    // cells write, on a communicator of their own; the first of them
    // gives the XDMF entry to all.
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    // (n_cells() of an empty filter is 2^32 - 1 in deal.II 9.4.)
    const bool         has_data     = filter.n_nodes() > 0;
    const unsigned int first_writer = Utilities::MPI::min(
      has_data ? rank : std::numeric_limits<unsigned int>::max(), comm);
    MPI_Comm  writers = MPI_COMM_NULL;
    const int ierr =
      MPI_Comm_split(comm, has_data ? 0 : MPI_UNDEFINED, rank, &writers);
    AssertThrowMPI(ierr);
    XDMFEntry entry;
    try
      {
        write_hdf5_file(
          comm, directory + "/" + file_name, [&](const std::string &temporary) {
            if (has_data)
              data_out.write_hdf5_parallel(filter, temporary, writers);
          });
        // The XDMF file sits beside the HDF5 file: a relative name.
        if (has_data)
          entry = data_out.create_xdmf_entry(filter, file_name, time, writers);
      }
    catch (...)
      {
        if (writers != MPI_COMM_NULL)
          MPI_Comm_free(&writers);
        throw;
      }
    if (writers != MPI_COMM_NULL)
      MPI_Comm_free(&writers);
    return Utilities::MPI::broadcast(comm, entry, first_writer);
  }



  void
  write_xdmf_file(const MPI_Comm                comm,
                  const std::string            &path,
                  const std::vector<XDMFEntry> &entries,
                  const ReferenceCell          &cell_type)
  {
    write_file(comm, path, [&](std::ostream &xdmf) {
      xdmf << "<?xml version=\"1.0\" ?>\n"
           << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
           << "<Xdmf Version=\"2.0\">\n"
           << "  <Domain>\n"
           << "    <Grid Name=\"CellTime\" GridType=\"Collection\" "
              "CollectionType=\"Temporal\">\n";
      for (const XDMFEntry &entry : entries)
        xdmf << entry.get_xdmf_content(3, cell_type);
      xdmf << "    </Grid>\n"
           << "  </Domain>\n"
           << "</Xdmf>\n";
    });
  }



  void
  remove_output_of_earlier_run(const MPI_Comm                    comm,
                               const std::string                &directory,
                               const dealii::ConditionalOStream &log)
  {
    unsigned int n_removed = 0;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        // With the temporary files of the run-wide ones, which a run
        // killed during a write leaves behind, and the lock test file
        // that MPI-IO (ROMIO) makes beside a parallel HDF5 file.
        const std::regex own_file(
          "(body-[12]|contact)(_[0-9]{3}(\\.[0-9]+)?\\.(vtu|pvtu|csv|h5)|"
          "\\.(pvd|xdmf))(\\.tmp(\\.locktest\\.[0-9]+)?)?|"
          "(summary\\.json|parameters\\.prm)\\.tmp");
        std::error_code error;
        for (const auto &entry :
             std::filesystem::directory_iterator(directory, error))
          if (entry.is_regular_file(error) &&
              std::regex_match(entry.path().filename().string(), own_file))
            n_removed += std::filesystem::remove(entry.path(), error);
      }
    n_removed = Utilities::MPI::broadcast(comm, n_removed, 0);
    if (n_removed > 0)
      log << "  removed " << n_removed
          << " output files of an earlier run from '" << directory << "'"
          << std::endl;
  }
} // namespace coulomb_adapt
