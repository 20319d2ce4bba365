#include <coulomb_adapt/contact/tighter_krylov_solve.h>

namespace coulomb_adapt
{
  bool
  repeat_krylov_solve_tighter(const unsigned int n_repeats,
                              const double       residual,
                              const double       residual_before_last_repeat)
  {
    if (n_repeats == 0)
      return true;
    // A repeat that gained less than a factor 10 for a factor 100 on the
    // tolerance has met another limit (round-off): a further one would
    // only cost a solve.
    return n_repeats < max_tighter_krylov_solves &&
           residual <= 0.1 * residual_before_last_repeat;
  }
} // namespace coulomb_adapt
