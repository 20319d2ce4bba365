#include <coulomb_adapt/app/small_block_allocation.h>

#include <cstdlib>
#include <cstring>

#ifdef __GLIBC__
#  include <malloc.h>
#endif

namespace coulomb_adapt
{
  bool
  turn_off_malloc_fastbins()
  {
#ifdef __GLIBC__
    const char *tunables = std::getenv("GLIBC_TUNABLES");
    if (tunables != nullptr &&
        std::strstr(tunables, "glibc.malloc.mxfast") != nullptr)
      return false;
    return mallopt(M_MXFAST, 0) == 1;
#else
    return false;
#endif
  }
} // namespace coulomb_adapt
