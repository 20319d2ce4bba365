#ifndef coulomb_adapt_output_body_output_h
#define coulomb_adapt_output_body_output_h

#include <deal.II/base/data_out_base.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/core/options.h>
#include <coulomb_adapt/indicator/recovered_stress.h>
#include <coulomb_adapt/output/file_writer.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /** The indicator's fields of a body, when it was computed. */
  struct BodyErrorFields
  {
    const Vector<float>   *indicator = nullptr;
    const Vector<float>   *density   = nullptr;
    const RecoveredStress *recovered = nullptr;
  };

  /**
   * Writes one body's fields per cycle, and an index of all cycles written
   * so far, so that ParaView shows the cycles as a time series (the cycle
   * number is the time). @p format "vtu": `<base>_<cycle>.pvtu` (+ one
   * `.vtu` per rank) indexed by `<base>.pvd`; "hdf5": `<base>_<cycle>.h5`
   * (all ranks write into one file) indexed by `<base>.xdmf`.
   */
  class BodyOutput
  {
  public:
    BodyOutput(const std::string &directory,
               const std::string &base_name,
               const OutputFormat format);

    void
    write(const ElasticBody     &body,
          const unsigned int     cycle,
          const BodyErrorFields &error_fields = BodyErrorFields());

    /**
     * Collective: the VTU piece of the last write(), written in the
     * background, made visible (renamed, listed in the .pvtu and .pvd
     * records), a write error thrown on every rank. write() does this
     * for the cycle before; the caller for the last one.
     */
    void
    finish_writing();

  private:
    const std::string                           directory;
    const std::string                           base_name;
    const OutputFormat                          format;
    std::vector<std::pair<double, std::string>> pvd_records;
    std::vector<XDMFEntry>                      xdmf_entries;
    /** The VTU output being written, and its cycle. */
    std::unique_ptr<VtuWrite> pending;
    unsigned int              pending_cycle = 0;
    MPI_Comm                  pending_comm  = MPI_COMM_NULL;
  };
} // namespace coulomb_adapt

#endif
