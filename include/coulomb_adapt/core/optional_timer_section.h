#ifndef coulomb_adapt_core_optional_timer_section_h
#define coulomb_adapt_core_optional_timer_section_h

#include <deal.II/base/timer.h>

#include <optional>
#include <string>

namespace coulomb_adapt
{
  /** While it lives, the section @p name of a TimerOutput, if there is one
   * (the library's functions take an optional timer). */
  class OptionalTimerSection
  {
  public:
    OptionalTimerSection(dealii::TimerOutput *timer, const std::string &name)
    {
      if (timer != nullptr)
        scope.emplace(*timer, name);
    }

  private:
    std::optional<dealii::TimerOutput::Scope> scope;
  };
} // namespace coulomb_adapt

#endif
