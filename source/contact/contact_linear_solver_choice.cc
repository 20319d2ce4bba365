#include <coulomb_adapt/contact/contact_linear_solver_choice.h>

namespace coulomb_adapt
{
  // The same choice in ContactSolver::setup(), which acts on it on every
  // mesh (a coarser nested-iteration mesh may fall below the threshold),
  // and in the program's log, which states it once per contact solve.
  ContactLinearSolverChoice
  choose_contact_linear_solver(const parameters::LinearSolver &parameters,
                               const types::global_dof_index   n_dofs)
  {
    const std::string direct =
      "direct (" + parameters.direct_solver + ", row-replacing system)";
    const std::string amg =
      "Krylov + AMG (eliminated system: CG without friction, GMRES with)";
    const std::string threshold =
      "'Linear solver/Maximum DoFs for direct contact' (" +
      std::to_string(parameters.max_dofs_for_direct_contact) + ")";
    ContactLinearSolverChoice choice;
    switch (parameters.type)
      {
        case LinearSolverType::direct:
          choice.description = direct + ": 'Linear solver/Type' = direct";
          break;
        case LinearSolverType::amg:
          choice.iterative   = true;
          choice.description = amg + ": 'Linear solver/Type' = amg";
          break;
        case LinearSolverType::automatic:
          choice.iterative =
            n_dofs > parameters.max_dofs_for_direct_contact;
          choice.description =
            (choice.iterative ? amg : direct) + ": " +
            std::to_string(n_dofs) + " DoFs " +
            (choice.iterative ? "> " : "<= ") + threshold +
            ", 'Linear solver/Type' = auto";
          break;
      }
    return choice;
  }
} // namespace coulomb_adapt
