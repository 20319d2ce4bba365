#ifndef coulomb_adapt_output_body_output_h
#define coulomb_adapt_output_body_output_h

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/recovered_stress.h>

#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /** The indicator's fields of a body, when it was computed. */
  struct BodyErrorFields
  {
    const Vector<float> *  indicator = nullptr;
    const Vector<float> *  density   = nullptr;
    const RecoveredStress *recovered = nullptr;
  };

  /**
   * Writes one body's fields per cycle as `<base>_<cycle>.pvtu` (+ one
   * `.vtu` per rank) and keeps `<base>.pvd` indexing all cycles written so
   * far, so that ParaView shows the cycles as a time series.
   */
  class BodyOutput
  {
  public:
    BodyOutput(const std::string &directory, const std::string &base_name);

    void
    write(const ElasticBody & body,
          const unsigned int  cycle,
          const BodyErrorFields &error_fields = BodyErrorFields());

  private:
    const std::string                           directory;
    const std::string                           base_name;
    std::vector<std::pair<double, std::string>> pvd_records;
  };
} // namespace coulomb_adapt

#endif
