#include <coulomb_adapt/core/parameter_error.h>

#include <sstream>

namespace coulomb_adapt
{
  ParameterError::ParameterError(const std::string &entry_path,
                                 const std::string &value,
                                 const std::string &allowed)
    : std::runtime_error("entry '" + entry_path + "' has the value '" + value +
                         "', which is not allowed: " + allowed)
  {}



  ParameterError::ParameterError(const std::string &message)
    : std::runtime_error(message)
  {}



  void
  require_parameter(const bool         condition,
                    const std::string &entry_path,
                    const double       value,
                    const std::string &allowed)
  {
    if (!condition)
      {
        std::ostringstream s;
        s << value;
        throw ParameterError(entry_path, s.str(), allowed);
      }
  }
} // namespace coulomb_adapt
