#ifndef coulomb_adapt_contact_contact_diagnosis_h
#define coulomb_adapt_contact_contact_diagnosis_h

#include <stdexcept>
#include <string>

namespace coulomb_adapt
{
  /**
   * The contact solver stopped with a diagnosis of its iteration: the
   * iteration limit, cycling sets, sets that converged above the
   * tolerance, a body not held by the sets of a step, a linear solve that
   * failed. These are judged on the contact states, which every rank holds
   * alike, so every rank throws; the program may try another start
   * (TwoBodyProblem::solve_contact). Other errors (bad input, a contact
   * node with Dirichlet data) are not diagnoses and end the run.
   */
  class ContactDiagnosis : public std::runtime_error
  {
  public:
    ContactDiagnosis(const std::string &message,
                     const unsigned int newton_steps)
      : std::runtime_error(message)
      , newton_steps(newton_steps)
    {}

    /** Newton steps run before the stop. */
    unsigned int newton_steps;
  };
} // namespace coulomb_adapt

#endif
