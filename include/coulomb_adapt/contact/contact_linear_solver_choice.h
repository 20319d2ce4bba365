#ifndef coulomb_adapt_contact_contact_linear_solver_choice_h
#define coulomb_adapt_contact_contact_linear_solver_choice_h

#include <deal.II/base/types.h>

#include <coulomb_adapt/core/parameters.h>

#include <string>

namespace coulomb_adapt
{
  /**
   * Which linear solver takes the contact Newton systems, and why: the
   * sparse direct solver on the row-replacing system, or Krylov + AMG on
   * the system with the contact conditions eliminated. 'Linear
   * solver/Type = auto' chooses by the DoFs of both bodies against
   * 'Maximum DoFs for direct contact' (the crossover measured in
   * benchmarks/contact/README.md, "Direct against Krylov + AMG: the
   * crossover"); direct and amg are taken as given.
   */
  struct ContactLinearSolverChoice
  {
    /** Krylov + AMG on the eliminated system. */
    bool iterative = false;
    /** For the log: the solver and the reason, e.g. "direct
     * (Amesos_Mumps): 7764 DoFs <= 'Linear solver/Maximum DoFs for direct
     * contact' (20000)". */
    std::string description;
  };

  ContactLinearSolverChoice
  choose_contact_linear_solver(const parameters::LinearSolver &parameters,
                               const types::global_dof_index   n_dofs);
} // namespace coulomb_adapt

#endif
