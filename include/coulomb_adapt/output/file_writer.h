#ifndef coulomb_adapt_output_file_writer_h
#define coulomb_adapt_output_file_writer_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <coulomb_adapt/output/vtu_pieces.h>

#include <functional>
#include <future>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Write the file @p path on rank 0 of @p comm: @p write fills the
   * stream, into "path.tmp", which is renamed to @p path once complete. A
   * reader (ParaView following a .pvd, a script polling summary.json)
   * never sees a half-written file, and a failed write leaves what an
   * earlier cycle wrote at @p path intact.
   *
   * Collective: every rank calls it, @p write runs on rank 0 only, and a
   * failure (the file cannot be opened, written or renamed: a full disk,
   * a directory in the way) throws on every rank with a message naming
   * the file and the system's reason ("No space left on device"), so
   * that no rank waits for another that has given up.
   */
  void
  write_file(const MPI_Comm                             comm,
             const std::string                         &path,
             const std::function<void(std::ostream &)> &write);

  /**
   * write_file by the calling process alone, with no communication: for
   * a record made while the run is failing, when another rank may never
   * reach a collective call. Returns the failure's message, empty on
   * success (the caller is already reporting an error).
   */
  std::string
  write_file_on_this_process(const std::string                         &path,
                             const std::function<void(std::ostream &)> &write);

  /**
   * DataOutInterface::write_vtu_with_pvtu_record for this rank's pieces
   * (each written by DataOutBase::write_vtu to its own file, by
   * concurrent tasks), made atomic and collective, in two halves, so that
   * the pieces can be encoded, compressed and written on a thread of
   * their own while the run goes on: an adaptive run's next cycle
   * (remeshing, contact solve) leaves one of two cores idle for much of
   * its time, and encoding and compressing the fields was most of the
   * output's time (benchmarks/adaptive_run).
   *
   * The pieces are numbered over all ranks, rank by rank (`BASE_CCC.N.vtu`;
   * with one piece per rank, N is the rank as in deal.II's names), and
   * `BASE_CCC.pvtu` lists them. Every rank needs at least one piece
   * (perhaps empty). The constructor (collective) names them and starts
   * writing this rank's to NAME.tmp: on a background thread, which makes
   * no MPI call, when @p in_background (and the thread can be started),
   * otherwise when finish() is called. finish() (collective) waits for
   * them; when every rank has written its own, it renames them and
   * writes the record through write_file, and returns the record's name
   * (relative to the directory, for a .pvd); otherwise it removes them
   * and throws the first rank's error, naming the file and the system's
   * reason, on every rank. An object destroyed without finish() (an
   * error has ended the run) waits for its thread and removes its
   * temporary files: no piece is left under its final name without its
   * record.
   */
  class VtuRecordWrite
  {
  public:
    VtuRecordWrite(const MPI_Comm                       comm,
                   VtuPieces                          &&pieces,
                   const dealii::DataOutBase::VtkFlags &flags,
                   const std::string                   &directory,
                   const std::string                   &base_name,
                   const unsigned int                   cycle,
                   const bool                           in_background);

    ~VtuRecordWrite();

    VtuRecordWrite(const VtuRecordWrite &) = delete;
    VtuRecordWrite &
    operator=(const VtuRecordWrite &) = delete;

    /** The record's name (relative to the directory, for a .pvd). */
    std::string
    finish(const MPI_Comm comm);

  private:
    /** Waits for this rank's pieces: the first failure's message, or "". */
    std::string
    wait_for_own_pieces();

    // On the heap, where the writing thread reads it, whatever happens
    // to this object.
    const std::shared_ptr<const VtuPieces> pieces;
    const dealii::DataOutBase::VtkFlags    flags;
    const std::string                      directory;
    const std::string                      record_name;
    std::vector<std::string>               piece_names;
    std::vector<std::string>               own_paths;
    std::future<std::string>               own_pieces_written;
    bool                                   finished = false;
  };

  /**
   * Write the HDF5 file @p path through @p write, which every rank of
   * @p comm calls with the temporary name to write to (deal.II's parallel
   * HDF5 writers are collective). The file is renamed to @p path once every
   * rank has returned without error, so that a reader of the XDMF file
   * never sees a half-written one. A failure on any rank throws the same
   * error, naming @p path and the reason, on every rank.
   */
  void
  write_hdf5_file(const MPI_Comm                                  comm,
                  const std::string                              &path,
                  const std::function<void(const std::string &)> &write);

  /**
   * DataOutInterface::write_hdf5_parallel of @p data_out (mesh and fields
   * in one file, `directory/file_name`, through write_hdf5_file). Returns
   * the file's XDMF entry at time @p time. Collective.
   */
  dealii::XDMFEntry
  write_hdf5(const MPI_Comm                        comm,
             const dealii::DataOutInterface<2, 2> &data_out,
             const std::string                    &directory,
             const std::string                    &file_name,
             const double                          time);

  /**
   * The XDMF file @p path (a temporal collection of @p entries, the cells
   * of type @p cell_type), written through write_file: what
   * DataOutInterface::write_xdmf_file writes, but atomically, and without
   * needing patches on rank 0. Collective.
   */
  void
  write_xdmf_file(const MPI_Comm                        comm,
                  const std::string                    &path,
                  const std::vector<dealii::XDMFEntry> &entries,
                  const dealii::ReferenceCell          &cell_type);

  /**
   * Remove the program's own per-cycle files (`body-1_CCC.vtu`,
   * `contact_CCC.csv`, `body-1_CCC.h5`, ..., their .tmp files, the .pvd
   * and .xdmf lists, and the .tmp files of summary.json and
   * parameters.prm that a killed run can leave) from
   * @p directory on rank 0 of @p comm, and say in @p log (rank 0's) how many. A run
   * into the directory of an earlier, longer one would otherwise leave
   * that run's later cycles beside this run's summary.json, as if they
   * were its own. Other files stay. Collective; call it before the first
   * cycle.
   */
  void
  remove_output_of_earlier_run(const MPI_Comm                    comm,
                               const std::string                &directory,
                               const dealii::ConditionalOStream &log);
} // namespace coulomb_adapt

#endif
