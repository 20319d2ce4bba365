#include <coulomb_adapt/core/optional_timer_section.h>
#include <coulomb_adapt/indicator/contact_error.h>
#include <coulomb_adapt/indicator/dirichlet_data_lift.h>
#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/indicator/kinematic_admissibility.h>

#include <cmath>
#include <limits>
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
            equilibrium                 = correct_contact_solution(*bodies[0],
                                                   *bodies[1],
                                                   *contact_solver,
                                                   mu,
                                                   solver_parameters,
                                                   ContactLoadForm::consistent);
            estimate.bernstein_traction = equilibrium.bernstein;
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



  namespace
  {
    // The bound for mu = 0 with a kinematic side U_c that may penetrate
    // between the mortar's nodes (kinematic_admissibility.h). With
    // e = ||sigma - sigma_c||, A^2 = sum_E ||sigma^ - sigma_c||_E^2 and
    // p^, g the pressure of sigma^ and the pointwise gap,
    //   e^2 <= A^2 + 2 int p^ g(U_c) + 2 int p |g^-(U_c)|   (p exact),
    // and with the opening delta, b = ||sigma(delta)||, S its computable
    // work, int p |g^-| <= e b + S, so that
    //   e <= b + sqrt(A^2 + 2 int p^ g+(U_c) + b^2 + 2 S) =: b + eta.
    // The cells get a_E^2 + c_E (c_E the contact term on E's faces, each
    // piece counted on both sides) and b^2 + 2 S in proportion to
    // ||sigma(delta)||_E^2; then (eta + b)^2 = (1 + gamma) eta^2 +
    // (1 + 1 / gamma) b^2 with gamma = b / eta splits the sum into cell
    // contributions. The seed's contact term (estimate.contact, nodal,
    // clipped) is added to this and to the exact error (3-8) as before.
    // Without penetration it is the hypercircle with the pointwise contact
    // term. With friction no bound is claimed: the penetration is measured
    // and reported only.
    void
    add_kinematic_admissibility(
      const std::array<const ElasticBody *, 2> &bodies,
      const MortarInterface                    &mortar,
      const CorrectedContactSolution           &equilibrium,
      const double                              mu,
      const double                              normalisation_squared,
      const parameters::LinearSolver           &solver_parameters,
      std::array<double, 2>                    &volume_squared,
      ErrorEstimate                            &estimate)
    {
      const std::array<const TrilinosWrappers::MPI::Vector *, 2> judged = {
        {&estimate.correction.displacement(0),
         &estimate.correction.displacement(1)}};
      // With mu = 0 the opening is chosen by the bound it gives, which
      // needs C = A^2 + 2 int p^ g+(U_c) (the pressure-gap term's cell
      // maps hold each piece on both sides: 2 int).
      std::optional<ContactErrorTerm> pressure_gap;
      double                          hypercircle_squared = 0;
      if (mu == 0)
        {
          pressure_gap = pressure_gap_term(mortar, equilibrium.fields, judged);
          hypercircle_squared = 2 * pressure_gap->integral;
          for (unsigned int b = 0; b < 2; ++b)
            hypercircle_squared += Utilities::MPI::sum(
              estimate.contribution_squared[b].l1_norm(),
              bodies[b]->triangulation().get_communicator());
        }
      const KinematicAdmissibility admissible =
        make_kinematically_admissible(mortar,
                                      bodies,
                                      judged,
                                      nodal_pressures(equilibrium.fields),
                                      solver_parameters,
                                      hypercircle_squared,
                                      mu == 0);
      estimate.penetration    = admissible.penetration;
      estimate.penetration_at = admissible.where;
      if (mu > 0)
        return;
      estimate.opening_applied   = admissible.opening_applied;
      estimate.opened_nodes      = admissible.n_opened_nodes;
      estimate.penetration_after = admissible.penetration_after;
      estimate.narrow_opening    = admissible.narrow;
      // sigma^'s pressure is >= 0 wherever its nodal values are (their
      // Bernstein form, on linear segments their interpolant); checked on
      // quadratic segments.
      if (mortar.slave_element_degree() > 1)
        estimate.negative_pressure =
          pressure_gap_negative_pressure(mortar, equilibrium.fields);
      const double opening = std::sqrt(admissible.opening_norm_squared);
      // S < -b^2 / 2 would make the opening's share negative; a larger S
      // only loosens the bound.
      const double opening_share =
        admissible.opened() ?
          1 + 2 * std::max(admissible.opening_work /
                             admissible.opening_norm_squared,
                           -0.5) :
          0.;

      double eta_squared = 0;
      for (unsigned int b = 0; b < 2; ++b)
        {
          Vector<double> &e2 = estimate.contribution_squared[b];
          if (admissible.opened())
            e2.add(opening_share, admissible.opening_squared[b]);
          const auto cells = owned_boundary_cell_indices(*bodies[b]);
          for (const auto &[id, value] : (b == 0 ? pressure_gap->slave_cells :
                                                   pressure_gap->master_cells))
            if (const auto c = cells.find(id); c != cells.end())
              e2(c->second) += value;
          volume_squared[b] =
            Utilities::MPI::sum(e2.l1_norm(),
                                bodies[b]->triangulation().get_communicator());
          eta_squared += volume_squared[b];
        }
      if (!admissible.opened())
        return;
      // eta = 0 (sigma^ = sigma(u^), no contact term): the bound is b.
      const double gamma = eta_squared > 0 ?
                             opening / std::sqrt(eta_squared) :
                             std::numeric_limits<double>::infinity();
      if (!std::isfinite(gamma))
        {
          for (unsigned int b = 0; b < 2; ++b)
            {
              estimate.contribution_squared[b] = admissible.opening_squared[b];
              volume_squared[b]                = Utilities::MPI::sum(
                estimate.contribution_squared[b].l1_norm(),
                bodies[b]->triangulation().get_communicator());
            }
          estimate.epsilon_opening = opening / std::sqrt(normalisation_squared);
          estimate.opening_work_relative =
            2 * admissible.opening_work / normalisation_squared;
          return;
        }
      for (unsigned int b = 0; b < 2; ++b)
        {
          Vector<double> &e2 = estimate.contribution_squared[b];
          e2 *= 1 + gamma;
          e2.add(1 + 1 / gamma, admissible.opening_squared[b]);
          volume_squared[b] =
            Utilities::MPI::sum(e2.l1_norm(),
                                bodies[b]->triangulation().get_communicator());
        }
      estimate.epsilon_opening = opening / std::sqrt(normalisation_squared);
      estimate.opening_work_relative =
        2 * admissible.opening_work / normalisation_squared;
    }
  } // namespace



  namespace
  {
    // The bound where u_c misses the displacement data between the nodes
    // (dirichlet_data_lift.h): e <= A + b, A^2 the sum of the cells'
    // contributions so far (the local problems measured sigma^ -
    // sigma(u_c + r)), b = ||sigma(r)||. Split into the cells as the
    // opening is: (A + b)^2 = (1 + gamma) A^2 + (1 + 1 / gamma) b^2 with
    // gamma = b / A, each cell's A and b parts in those ratios.
    void
    add_dirichlet_data_lift(const std::array<const ElasticBody *, 2> &bodies,
                            const double           normalisation_squared,
                            std::array<double, 2> &volume_squared,
                            ErrorEstimate         &estimate)
    {
      std::array<DirichletDataLift, 2> lift;
      double                           lift_squared = 0;
      for (unsigned int b = 0; b < 2; ++b)
        {
          lift[b] = dirichlet_data_lift(*bodies[b],
                                        estimate.correction.displacement(b));
          lift_squared += lift[b].norm_squared;
        }
      if (lift_squared == 0)
        return;
      estimate.epsilon_dirichlet_lift =
        std::sqrt(lift_squared /
                  (normalisation_squared > 0 ? normalisation_squared : 1.));
      const double a = std::sqrt(volume_squared[0] + volume_squared[1]);
      const double c = std::sqrt(lift_squared);
      for (unsigned int b = 0; b < 2; ++b)
        {
          Vector<double> &e2 = estimate.contribution_squared[b];
          if (a > 0)
            {
              e2 *= 1 + c / a;
              e2.add(1 + a / c, lift[b].squared);
            }
          else
            {
              e2 = lift[b].squared;
            }
          volume_squared[b] =
            Utilities::MPI::sum(e2.l1_norm(),
                                bodies[b]->triangulation().get_communicator());
        }
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

    // The lift reads the displacement data's gradient: checked once per
    // body, before the equilibration and the lift's energy use it.
    if (minimisation.lift_displacement_data)
      for (const ElasticBody *body : bodies)
        check_displacement_data_gradient(*body);
    else
      for (const ElasticBody *body : bodies)
        estimate.displacement_data_unlifted =
          estimate.displacement_data_unlifted ||
          !body->description().displacement_data_interpolated_exactly;

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
    if (estimate.has_contact)
      add_kinematic_admissibility(bodies,
                                  contact_solver->mortar_interface(),
                                  equilibrium,
                                  mu,
                                  normalisation_squared,
                                  solver_parameters,
                                  volume_squared,
                                  estimate);
    if (minimisation.lift_displacement_data)
      add_dirichlet_data_lift(bodies,
                              normalisation_squared,
                              volume_squared,
                              estimate);
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
