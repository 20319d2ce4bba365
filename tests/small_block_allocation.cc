// turn_off_malloc_fastbins (app/small_block_allocation.h) stops glibc from
// keeping freed small blocks in fastbins, and leaves a user's own
// GLIBC_TUNABLES setting alone.
//
// Fastbins hold a freed block once the per-thread cache of its size is
// full (7 blocks): mallinfo2()'s fsmblks counts the bytes they hold.
// 1,000 blocks of 48 bytes are allocated and freed (with a guard block
// after them, so that they are not merged into the top of the heap):
// with fastbins on, most of them land there; after the call, none.

#include <coulomb_adapt/app/small_block_allocation.h>

#include <malloc.h>

#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace
{
  // Bytes in fastbins after 1,000 small blocks were freed.
  std::size_t
  fastbin_bytes_after_churn()
  {
    std::vector<void *> blocks(1000);
    for (auto &b : blocks)
      b = std::malloc(48);
    void *guard = std::malloc(48);
    for (auto &b : blocks)
      std::free(b);
    const std::size_t bytes = mallinfo2().fsmblks;
    std::free(guard);
    malloc_trim(0);
    return bytes;
  }

  void
  check(const bool condition, const char *what)
  {
    if (!condition)
      throw std::runtime_error(what);
  }
} // namespace

int
main()
{
  using namespace coulomb_adapt;
  const std::size_t before = fastbin_bytes_after_churn();
  std::cout << "fastbins used before the call: " << (before > 0 ? "yes" : "no")
            << std::endl;
  check(before > 0, "glibc's default keeps freed small blocks in fastbins");

  setenv("GLIBC_TUNABLES", "glibc.malloc.mxfast=64", 1);
  const bool made_with_tunables = turn_off_malloc_fastbins();
  std::cout << "with the user's glibc.malloc.mxfast: setting made "
            << (made_with_tunables ? "yes" : "no") << ", fastbins used "
            << (fastbin_bytes_after_churn() > 0 ? "yes" : "no") << std::endl;
  check(!made_with_tunables, "the user's tuning is kept");

  unsetenv("GLIBC_TUNABLES");
  const bool        made  = turn_off_malloc_fastbins();
  const std::size_t after = fastbin_bytes_after_churn();
  std::cout << "without: setting made " << (made ? "yes" : "no")
            << ", fastbins used " << (after > 0 ? "yes" : "no") << std::endl;
  check(made && after == 0, "no freed block is kept in a fastbin");
}
