#ifndef coulomb_adapt_core_version_h
#define coulomb_adapt_core_version_h

#include <string>

namespace coulomb_adapt
{
  /**
   * The program's version: `git describe` of the source tree at build time.
   */
  std::string
  version();
} // namespace coulomb_adapt

#endif
