#include <coulomb_adapt/contact/contact_state.h>

namespace coulomb_adapt
{
  std::string
  to_string(const ContactStatus status)
  {
    switch (status)
      {
        case ContactStatus::open:
          return "open";
        case ContactStatus::stick:
          return "stick";
        default:
          return "slip";
      }
  }
} // namespace coulomb_adapt
