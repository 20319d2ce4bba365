#ifndef coulomb_adapt_app_small_block_allocation_h
#define coulomb_adapt_app_small_block_allocation_h

namespace coulomb_adapt
{
  /**
   * Turn off glibc's fastbins (mallopt(M_MXFAST, 0)): freed small blocks
   * go to glibc's per-thread cache and its ordinary bins instead of lists
   * that a later larger request must first merge (malloc_consolidate).
   *
   * deal.II's DataOut::build_patches() allocates and frees small blocks per
   * cell between larger ones, and spent about a third of its time in
   * malloc_consolidate and its neighbours. Without fastbins the output of
   * prm/blocks.prm at epsilon_0 = 0.25 % took 0.81 s instead of
   * 1.06-1.11 s, the contact solve and the estimators took the same time
   * or less, and the peak memory was 0-4 MB lower
   * (benchmarks/adaptive_run).
   *
   * Nothing changes when the user tunes it (GLIBC_TUNABLES names
   * glibc.malloc.mxfast) or with another C library. Returns whether the
   * setting was made.
   */
  bool
  turn_off_malloc_fastbins();
} // namespace coulomb_adapt

#endif
