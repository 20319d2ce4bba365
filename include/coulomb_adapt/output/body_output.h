#ifndef coulomb_adapt_output_body_output_h
#define coulomb_adapt_output_body_output_h

#include <coulomb_adapt/bodies/elastic_body.h>

#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
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
    write(const ElasticBody &body, const unsigned int cycle);

  private:
    const std::string                           directory;
    const std::string                           base_name;
    std::vector<std::pair<double, std::string>> pvd_records;
  };
} // namespace coulomb_adapt

#endif
