#include <coulomb_adapt/core/optional_timer_section.h>
#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <cmath>
#include <optional>

namespace coulomb_adapt
{
  namespace
  {
    // The contact traction of the equilibrated stresses at the Gauss
    // points of the mortar overlaps: R_c on the slave cells, -R_c at the
    // projected points on the master cells (the same points and weights as
    // the consistent load of the corrected problem, so that the edge
    // moments are those of the FE load vector).
    std::array<ContactTractionData, 2>
    contact_traction_data(const MortarInterface                &mortar,
                          const std::vector<ContactNodeFields> &fields)
    {
      const auto points = mortar.overlap_quadrature(
        contact_traction_points_per_overlap(mortar.slave_element_degree()));
      const auto R = contact_traction_at(mortar, fields, points);
      std::array<ContactTractionData, 2> data;
      for (unsigned int q = 0; q < points.size(); ++q)
        {
          const auto &overlap = mortar.overlaps()[points[q].overlap];
          data[0][mortar.slave_segment_list()[overlap.slave_segment].cell]
            .push_back({points[q].slave_point, points[q].weight, R[q]});
          data[1][mortar.master_segment_list()[overlap.master_segment].cell]
            .push_back({points[q].master_point, points[q].weight, -R[q]});
        }
      return data;
    }
  } // namespace



  namespace
  {
    // The kinematic side is the seed's corrected solution (the FE solution
    // when its reactions are in the Coulomb cone); the static side is
    // equilibrated from the solution under the consistent contact load,
    // whose Neumann data R_c lies in the cone between the nodes. (The
    // mortar load's dual-basis traction does not: at the ends of the
    // contact zone it changes sign between two nodes.) Returns the static
    // side; the kinematic side and the contact term go to @p estimate, the
    // static side's contact tractions to @p contact.
    CorrectedContactSolution
    correct_contact_solutions(const std::array<const ElasticBody *, 2> &bodies,
                              const ContactSolution          *contact_solver,
                              const double                    mu,
                              const parameters::LinearSolver &solver_parameters,
                              const ErrorEstimateOptions     &options,
                              ErrorEstimate                  &estimate,
                              std::array<ContactTractionData, 2> &contact)
    {
      CorrectedContactSolution equilibrium;
      if (estimate.has_contact)
        {
          {
            const OptionalTimerSection section(options.timer,
                                               "error indicator: correction");
            estimate.correction = corrected_contact_fields(
              bodies, *contact_solver, mu, solver_parameters, options);
            equilibrium = correct_contact_solution(*bodies[0],
                                                   *bodies[1],
                                                   *contact_solver,
                                                   mu,
                                                   solver_parameters,
                                                   ContactLoadForm::consistent);
          }
          const OptionalTimerSection section(options.timer,
                                             "error indicator: contributions");
          estimate.contact =
            integrate_contact_error(contact_solver->mortar_interface(),
                                    estimate.correction.fields,
                                    mu);
          contact = contact_traction_data(contact_solver->mortar_interface(),
                                          equilibrium.fields);
        }
      else
        {
          estimate.correction.fe_displacement = {
            {&bodies[0]->solution(), &bodies[1]->solution()}};
          equilibrium.fe_displacement = estimate.correction.fe_displacement;
        }
      return equilibrium;
    }



    // Body @p b's cell errors, defects and optimisation figures into
    // @p estimate; returns the body's sum of the cell errors (every rank).
    double
    add_body_errors(const ElasticBody        &body,
                    const unsigned int        b,
                    EquilibratedStressErrors &errors,
                    ErrorEstimate            &estimate)
    {
      estimate.optimisation_parameters += errors.optimisation_parameters;
      estimate.optimisation_steps =
        std::max(estimate.optimisation_steps, errors.optimisation_steps);
      estimate.exact_minimisation_too_large =
        estimate.exact_minimisation_too_large ||
        errors.exact_minimisation_too_large;
      estimate.relaxed_equilibration[b]    = errors.relaxed;
      estimate.classical_tractions_kept[b] = errors.optimisation_kept_classical;
      estimate.contribution_squared[b].swap(errors.error_squared);
      estimate.node_system_defect =
        std::max(estimate.node_system_defect, errors.node_system_defect);
      estimate.local_problem_defect =
        std::max(estimate.local_problem_defect, errors.local_problem_defect);
      estimate.uncarried_held_reaction =
        std::max(estimate.uncarried_held_reaction,
                 errors.uncarried_held_reaction);
      return Utilities::MPI::sum(estimate.contribution_squared[b].l1_norm(),
                                 body.triangulation().get_communicator());
    }
  } // namespace



  ErrorEstimate
  estimate_error_cre(const std::array<const ElasticBody *, 2> &bodies,
                     const ContactSolution                    *contact_solver,
                     const double                              mu,
                     const unsigned int                        degree_increase,
                     const bool                      optimise_tractions,
                     const bool                      relax_equilibration,
                     const CreMinimisation          &minimisation,
                     const parameters::LinearSolver &solver_parameters,
                     const ErrorEstimateOptions     &options)
  {
    ErrorEstimate estimate;
    estimate.estimator   = ErrorEstimator::cre;
    estimate.has_contact = (contact_solver != nullptr);
    estimate.evaluation_degree_increase =
      minimisation.evaluation_degree_increase;
    estimate.relaxed_equilibration_requested = relax_equilibration;
    std::array<ContactTractionData, 2> contact;
    const CorrectedContactSolution     equilibrium =
      correct_contact_solutions(bodies,
                                contact_solver,
                                mu,
                                solver_parameters,
                                options,
                                estimate,
                                contact);

    std::array<double, 2> volume_squared;
    double                normalisation_squared = 0, before_squared = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const OptionalTimerSection section(options.timer,
                                           "error indicator: equilibration");
        EquilibratedStressErrors   errors =
          equilibrated_stress_errors(*bodies[b],
                                     equilibrium.displacement(b),
                                     estimate.correction.displacement(b),
                                     contact[b],
                                     degree_increase,
                                     optimise_tractions,
                                     relax_equilibration,
                                     minimisation,
                                     options.timer);
        before_squared += errors.error_squared_before_optimisation;
        normalisation_squared += errors.sum_norm_squared;
        volume_squared[b] = add_body_errors(*bodies[b], b, errors, estimate);
      }

    const OptionalTimerSection section(options.timer,
                                       "error indicator: contributions");
    finish_error_estimate(bodies,
                          volume_squared,
                          normalisation_squared,
                          estimate);
    // With the same normalisation D (that of the optimised sigma^).
    estimate.epsilon_before_optimisation =
      std::sqrt((before_squared + 2 * std::max(0., estimate.contact.integral)) /
                (normalisation_squared > 0 ? normalisation_squared : 1.));
    return estimate;
  }
} // namespace coulomb_adapt
