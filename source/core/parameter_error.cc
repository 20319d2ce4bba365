#include <deal.II/base/exceptions.h>

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
      throw ParameterError(entry_path, format_value(value), allowed);
  }



  std::string
  format_value(const double value)
  {
    std::ostringstream s;
    s << value;
    return s.str();
  }



  std::string
  user_message(const std::exception &e)
  {
    std::string text = e.what();
    if (const auto *dealii_exception =
          dynamic_cast<const dealii::ExceptionBase *>(&e))
      {
        std::ostringstream s;
        dealii_exception->print_info(s);
        text = s.str();
      }
    const auto first = text.find_first_not_of(" \n");
    const auto last  = text.find_last_not_of(" \n");
    return first == std::string::npos ? "" :
                                        text.substr(first, last - first + 1);
  }
} // namespace coulomb_adapt
