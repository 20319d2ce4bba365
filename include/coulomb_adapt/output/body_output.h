#ifndef coulomb_adapt_output_body_output_h
#define coulomb_adapt_output_body_output_h

#include <deal.II/base/data_out_base.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/core/options.h>
#include <coulomb_adapt/indicator/recovered_stress.h>

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

  private:
    const std::string                           directory;
    const std::string                           base_name;
    const OutputFormat                          format;
    std::vector<std::pair<double, std::string>> pvd_records;
    std::vector<XDMFEntry>                      xdmf_entries;
  };
} // namespace coulomb_adapt

#endif
