#ifndef coulomb_adapt_app_finiteness_h
#define coulomb_adapt_app_finiteness_h

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>

namespace coulomb_adapt
{
  /**
   * A number that left the range of doubles: an infinity or a NaN after a
   * solve or an estimate, or squares that underflow to zero or lose their
   * precision (subnormal numbers). The message names the body and the
   * quantity; the run stops rather than write or adapt on it.
   */
  class NonFiniteResult : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * After a solve: every displacement of both bodies finite, and with a
   * @p contact_solver (may be null) every contact node's pressure,
   * tangential traction, gap and slip. Collective: every rank throws the
   * same NonFiniteResult, or none does.
   */
  void
  check_finite_solution(
    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies,
    const ContactSolver                               *contact_solver);

  /**
   * After an error estimate: epsilon and its parts, the normalisation D^2
   * and every element contribution finite; D^2 > 0 when a body moves; no
   * contribution subnormal (its square lost its digits). Collective.
   */
  void
  check_finite_estimate(
    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies,
    const ErrorEstimate                               &estimate);
} // namespace coulomb_adapt

#endif
