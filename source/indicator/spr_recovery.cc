#include <coulomb_adapt/indicator/recovered_stress.h>

namespace coulomb_adapt
{
  // Placeholder until the patch recovery lands: refuse rather than
  // pretend.
  void
  RecoveredStress::recover_spr(const TrilinosWrappers::MPI::Vector &)
  {
    AssertThrow(false,
                ExcMessage("SPR stress recovery is not implemented yet; use "
                           "'Error indicator/Recovery = zz'."));
  }
} // namespace coulomb_adapt
