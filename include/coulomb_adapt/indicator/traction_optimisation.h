#ifndef coulomb_adapt_indicator_traction_optimisation_h
#define coulomb_adapt_indicator_traction_optimisation_h

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/equilibration_mesh.h>
#include <coulomb_adapt/indicator/local_neumann_problem.h>

#include <vector>

namespace coulomb_adapt
{
  namespace equilibration
  {
    class LocalProblemLoads;

    /** Local Neumann problems of one degree and the loads of the edge
     * tractions on them. */
    struct LocalProblems
    {
      const LocalNeumannProblem &local;
      const LocalProblemLoads   &loads;
    };

    /** Steps 5 and 6: the free parameters that minimise the estimate (see
     * the .cc; the faces' edge bubbles of degree p + 1 among them when
     * @p with_bubbles, and the modes that relax the prolongation
     * conditions when @p relaxed), cell by cell on the threads deal.II may use (with a
     * copy of @p local each), and the errors at the minimum in @p result
     * (error_squared, sum_norm_squared and the classical estimate). The
     * faces keep the classical moments. With @p timer, the cells' quadratic
     * forms, the parameters' matrix (built on the calling thread while
     * the forms are computed) and their assembly into it are timed in
     * "error indicator: cell forms".
     *
     * With @p evaluation (local problems of a higher degree than @p local,
     * and their loads), the errors at the minimum come from those instead
     * of the minimisation's quadratic forms: the minimum is where the
     * local problems of @p local's degree see least of sigma^, so their
     * estimate there is low by more than their discretisation error
     * elsewhere (doc/indicator.md section 4b). */
    void
    optimise_free_parameters(const ElasticBody                   &body,
                             const std::vector<CellData>         &cells,
                             const std::vector<FaceData>         &faces,
                             const LocalNeumannProblem           &local,
                             const TrilinosWrappers::MPI::Vector &u_kinematic,
                             const LocalProblemLoads             &loads,
                             const bool                           with_bubbles,
                             const bool                           relaxed,
                             const CreMinimisation               &minimisation,
                             EquilibratedStressErrors            &result,
                             const LocalProblems *evaluation = nullptr,
                             TimerOutput         *timer      = nullptr);
  } // namespace equilibration
} // namespace coulomb_adapt

#endif
