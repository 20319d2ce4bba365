#ifndef coulomb_adapt_core_parameter_error_h
#define coulomb_adapt_core_parameter_error_h

#include <stdexcept>
#include <string>

namespace coulomb_adapt
{
  /**
   * A value in the parameter file (or in a `-s` override) that has the right
   * type but is not allowed, e.g. a Poisson ratio of 0.5. The message names
   * the entry by its full path, the offending value and what is allowed; the
   * file name is added by whoever reads the file.
   */
  class ParameterError : public std::runtime_error
  {
  public:
    ParameterError(const std::string &entry_path,
                   const std::string &value,
                   const std::string &allowed);

    ParameterError(const std::string &message);
  };

  /**
   * @p value as a message shows it (6 significant digits: 0.95, not
   * 0.94999999999999996).
   */
  std::string
  format_value(const double value);

  /**
   * Throw a ParameterError for @p entry_path unless @p condition holds.
   */
  void
  require_parameter(const bool         condition,
                    const std::string &entry_path,
                    const double       value,
                    const std::string &allowed);

  /**
   * The part of @p e meant for a user: for a deal.II exception its
   * "additional information" without source location and stack trace,
   * otherwise what().
   */
  std::string
  user_message(const std::exception &e);
} // namespace coulomb_adapt

#endif
