// repeat_krylov_solve_tighter (contact/tighter_krylov_solve.h): unchanged
// sets whose residual misses the tolerance after a Krylov solve.
//  - the first repeat is always made, whatever the residual;
//  - a second one only if the first lowered the residual at least
//    tenfold: the measured hertz sequence (4.82e-9 -> 1.21e-10, 40x) gets
//    it, a repeat that gained 1.3x (6.36e-12 -> 5e-12) does not; the
//    bound itself (exactly 10x) does, 9.9x does not;
//  - never a third, however much the second gained;
//  - each repeat is 100 times tighter: 1e-12 |b| -> 1e-14 -> 1e-16.
// 1 rank.

#include <coulomb_adapt/contact/tighter_krylov_solve.h>

#include "test_utilities.h"

#include <iomanip>
#include <string>

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::setprecision(4);

  bool all_right = true;
  auto check     = [&](const std::string &what,
                   const unsigned int n_repeats,
                   const double       residual,
                   const double       before,
                   const bool         expected) {
    const bool repeat =
      repeat_krylov_solve_tighter(n_repeats, residual, before);
    all_right = all_right && repeat == expected;
    out << what << ": repeats so far " << n_repeats << ", residual " << residual
        << ", before the last repeat " << before << " -> "
        << (repeat ? "repeat" : "stop") << (repeat == expected ? "" : "  WRONG")
        << std::endl;
  };

  check("first, large residual", 0, 1e-3, 0, true);
  check("first, small residual", 0, 1e-15, 0, true);
  check("hertz 1.3e6 DoFs", 1, 1.21e-10, 4.82e-9, true);
  check("gained 1.3x", 1, 5e-12, 6.36e-12, false);
  check("gained exactly 10x", 1, 1e-11, 1e-10, true);
  check("gained 9.9x", 1, 1e-11, 9.9e-11, false);
  check("third", 2, 1e-20, 1e-10, false);

  double tolerance = 1e-12;
  out << "Krylov tolerance on |b|: " << tolerance;
  for (unsigned int r = 0; r < max_tighter_krylov_solves; ++r)
    {
      tolerance *= tighter_krylov_factor;
      out << " -> " << tolerance;
    }
  out << std::endl;
  all_right = all_right && max_tighter_krylov_solves == 2 &&
              std::abs(tolerance - 1e-16) <= 1e-30;

  AssertThrow(all_right, ExcMessage("the repeat rule is wrong"));
  return 0;
}
