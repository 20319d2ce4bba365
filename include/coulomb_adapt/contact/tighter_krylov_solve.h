#ifndef coulomb_adapt_contact_tighter_krylov_solve_h
#define coulomb_adapt_contact_tighter_krylov_solve_h

namespace coulomb_adapt
{
  /**
   * The rule for a Newton step whose sets came out unchanged from a Krylov
   * solve but whose complementarity residual misses max(Contact/Tolerance,
   * round-off floor): the Krylov tolerance on |b| does not bound the
   * multipliers node by node, so the same system is solved again from its
   * solution with the tolerance times tighter_krylov_factor (1e-12 |b|,
   * then 1e-14, then 1e-16). The first repeat is always made; the second
   * only if the first lowered the residual at least tenfold, i.e. the
   * residual still follows the linear solve. Measured (benchmarks/
   * adaptive_run, 21st session): hertz refine 0.25 %, 1.3e6 DoFs, 4.8e-9
   * after 1e-12 |b|, 1.2e-10 after 1e-14 (where the run used to stop, above
   * the tolerance 1e-10), 3.7e-12 after 1e-16.
   *
   * @p n_repeats: repeats of this step's solve so far; @p residual: after
   * the last solve; @p residual_before_last_repeat: before the last repeat
   * (unused when @p n_repeats is 0).
   */
  bool
  repeat_krylov_solve_tighter(const unsigned int n_repeats,
                              const double       residual,
                              const double       residual_before_last_repeat);

  /** The factor on the Krylov tolerance of each repeat. */
  constexpr double tighter_krylov_factor = 1e-2;

  /** At most this many repeats of one step's solve. */
  constexpr unsigned int max_tighter_krylov_solves = 2;
} // namespace coulomb_adapt

#endif
