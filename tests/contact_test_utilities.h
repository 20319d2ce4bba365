// A contact scene set up and solved, for the contact tests.
#ifndef coulomb_adapt_tests_contact_test_utilities_h
#define coulomb_adapt_tests_contact_test_utilities_h

#include <deal.II/base/conditional_ostream.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

#include <iostream>
#include <memory>
#include <sstream>

namespace coulomb_adapt
{
  namespace testing
  {
    struct SolvedContactProblem
    {
      ParameterHandler                            prm;
      Parameters                                  parameters;
      std::unique_ptr<Scene>                      scene;
      std::array<std::unique_ptr<ElasticBody>, 2> bodies;
      std::unique_ptr<ContactSolver>              solver;
      ContactSolverReport                         report;
      /** The Newton log (not printed: iteration details may vary). */
      std::ostringstream log;
    };

    /** The scene's bodies set up and assembled, the solver created but
     * not run. */
    inline std::unique_ptr<SolvedContactProblem>
    solve_contact_setup(
      const std::vector<std::pair<std::string, std::string>> &settings)
    {
      auto p        = std::make_unique<SolvedContactProblem>();
      p->parameters = make_parameters(p->prm, settings);
      p->scene      = scenes::create_scene(p->parameters, p->prm);
      for (unsigned int b = 0; b < 2; ++b)
        {
          p->bodies[b] = std::make_unique<ElasticBody>(
            MPI_COMM_WORLD,
            *p->scene,
            b,
            p->parameters.mesh.cell_type,
            p->parameters.mesh.global_refinements,
            p->parameters.finite_elements);
          p->bodies[b]->setup_system();
          p->bodies[b]->assemble_system();
        }
      static ConditionalOStream quiet(std::cout, false);
      p->solver = std::make_unique<ContactSolver>(*p->bodies[0],
                                                  *p->bodies[1],
                                                  p->parameters.contact,
                                                  p->parameters.linear_solver,
                                                  quiet);
      return p;
    }

    /** The same, solved from the initial gap. */
    inline std::unique_ptr<SolvedContactProblem>
    solve_contact(
      const std::vector<std::pair<std::string, std::string>> &settings)
    {
      auto p    = solve_contact_setup(settings);
      p->report = p->solver->solve();
      return p;
    }
  } // namespace testing
} // namespace coulomb_adapt

#endif
