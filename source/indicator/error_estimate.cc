#include <deal.II/base/timer.h>

#include <coulomb_adapt/core/optional_timer_section.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <cmath>
#include <functional>
#include <map>
#include <optional>

namespace coulomb_adapt
{
  std::map<CellId, unsigned int>
  owned_boundary_cell_indices(const ElasticBody &body)
  {
    std::map<CellId, unsigned int> indices;
    for (const auto &cell : body.triangulation().active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        indices.emplace(cell->id(), cell->active_cell_index());
    return indices;
  }



  namespace
  {
    // Per cell: int (sigma~ - sigma_c) K^-1 (sigma~ - sigma_c) into
    // @p difference, and the global int (sigma~ + sigma_c) K^-1 (...)
    // returned. The quadrature of the body integrates these exactly on
    // affine cells (sigma~ has the degree p of the displacement).
    double
    volume_terms(const QuadratureStress &raw_stress,
                 const RecoveredStress  &recovered,
                 Vector<double>         &difference)
    {
      const ElasticBody        &body     = raw_stress.body();
      const ElasticMaterial    &material = body.material();
      std::vector<Tensor<1, 3>> smoothed(raw_stress.n_points());

      difference.reinit(body.triangulation().n_active_cells());
      double       sum_norm   = 0;
      unsigned int owned_cell = 0;
      for (const auto &cell : recovered.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            recovered.get_quadrature_values(cell, smoothed);
            double cell_difference = 0;
            for (unsigned int q = 0; q < raw_stress.n_points(); ++q)
              {
                const SymmetricTensor<2, 2> sigma_c =
                  stress_tensor(raw_stress.stress(owned_cell, q));
                const SymmetricTensor<2, 2> sigma_s =
                  stress_tensor(smoothed[q]);
                const SymmetricTensor<2, 2> minus = sigma_s - sigma_c;
                const SymmetricTensor<2, 2> plus  = sigma_s + sigma_c;
                const double                JxW = raw_stress.JxW(owned_cell, q);
                cell_difference += minus * material.strain(minus) * JxW;
                sum_norm += plus * material.strain(plus) * JxW;
              }
            difference(cell->active_cell_index()) = cell_difference;
            ++owned_cell;
          }
      AssertDimension(owned_cell, raw_stress.n_cells());
      return Utilities::MPI::sum(sum_norm,
                                 body.triangulation().get_communicator());
    }
  } // namespace



  CorrectedContactSolution
  corrected_contact_fields(const std::array<const ElasticBody *, 2> &bodies,
                           const ContactSolution                    &contact,
                           const double                              mu,
                           const parameters::LinearSolver &solver_parameters,
                           const ErrorEstimateOptions     &options)
  {
    if (options.known_correction != nullptr)
      return *options.known_correction;
    return correct_contact_solution(
      *bodies[0], *bodies[1], contact, mu, solver_parameters);
  }



  void
  finish_error_estimate(const std::array<const ElasticBody *, 2> &bodies,
                        const std::array<double, 2> &volume_squared,
                        const double                 normalisation_squared,
                        ErrorEstimate               &estimate)
  {
    // The contact term on the contact faces of each side's cells.
    if (estimate.has_contact)
      for (unsigned int b = 0; b < 2; ++b)
        {
          const auto cells = owned_boundary_cell_indices(*bodies[b]);
          for (const auto &[id, value] :
               (b == 0 ? estimate.contact.slave_cells :
                         estimate.contact.master_cells))
            if (const auto c = cells.find(id); c != cells.end())
              estimate.contribution_squared[b](c->second) += value;
        }

    estimate.normalisation_squared = normalisation_squared;
    const double D2 = normalisation_squared > 0 ? normalisation_squared : 1.;
    for (unsigned int b = 0; b < 2; ++b)
      estimate.epsilon_volume[b] = std::sqrt(volume_squared[b] / D2);
    estimate.epsilon_contact =
      std::sqrt(std::max(0., 2 * estimate.contact.integral) / D2);
    estimate.epsilon = std::sqrt(
      (volume_squared[0] + volume_squared[1] + 2 * estimate.contact.integral) /
      D2);

    for (unsigned int b = 0; b < 2; ++b)
      {
        const auto n = bodies[b]->triangulation().n_active_cells();
        estimate.indicator[b].reinit(n);
        estimate.density[b].reinit(n);
        for (const auto &cell :
             bodies[b]->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const auto   i  = cell->active_cell_index();
              const double e2 = estimate.contribution_squared[b](i) / D2;
              estimate.indicator[b](i) = std::sqrt(std::max(0., e2));
              estimate.density[b](i)   = e2 / cell->measure();
            }
      }
  }



  namespace
  {
    using EstimatorFunction =
      std::function<ErrorEstimate(const std::array<const ElasticBody *, 2> &,
                                  const ContactSolution *,
                                  const double,
                                  const parameters::ErrorIndicator &,
                                  const parameters::LinearSolver &,
                                  const ErrorEstimateOptions &)>;

    // zz and spr: the recovery-based estimator of the seed with either
    // smoothing.
    template <StressRecoveryMethod recovery>
    ErrorEstimate
    recovery_estimate(const std::array<const ElasticBody *, 2> &bodies,
                      const ContactSolution                    *contact,
                      const double                              mu,
                      const parameters::ErrorIndicator &,
                      const parameters::LinearSolver &solver_parameters,
                      const ErrorEstimateOptions     &options)
    {
      return estimate_error(
        bodies, contact, mu, recovery, solver_parameters, options);
    }

    ErrorEstimate
    cre_estimate(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolution                    *contact,
                 const double                              mu,
                 const parameters::ErrorIndicator         &indicator_parameters,
                 const parameters::LinearSolver           &solver_parameters,
                 const ErrorEstimateOptions               &options)
    {
      return estimate_error_cre(
        bodies,
        contact,
        mu,
        indicator_parameters.cre_degree_increase,
        indicator_parameters.cre_traction_optimisation,
        indicator_parameters.cre_relaxed_equilibration,
        {indicator_parameters.cre_minimisation_tolerance,
         indicator_parameters.cre_exact_minimisation_up_to,
         indicator_parameters.cre_evaluation_degree_increase,
         indicator_parameters.cre_lift_displacement_data},
        solver_parameters,
        options);
    }

    // The registry of the estimators of 'Error indicator/Estimator': one
    // line each (the names are in core/error_estimator.cc).
    const std::map<ErrorEstimator, EstimatorFunction> &
    registered_estimators()
    {
      static const std::map<ErrorEstimator, EstimatorFunction> estimators = {
        {ErrorEstimator::zz,
         recovery_estimate<StressRecoveryMethod::l2_projection>},
        {ErrorEstimator::spr, recovery_estimate<StressRecoveryMethod::spr>},
        {ErrorEstimator::cre, cre_estimate}};
      return estimators;
    }
  } // namespace



  ErrorEstimate
  estimate_error(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolution                    *contact_solver,
                 const double                              mu,
                 const ErrorEstimator                      estimator,
                 const parameters::ErrorIndicator         &indicator_parameters,
                 const parameters::LinearSolver           &solver_parameters,
                 const ErrorEstimateOptions               &options)
  {
    const auto entry = registered_estimators().find(estimator);
    AssertThrow(entry != registered_estimators().end(),
                ExcMessage("no error estimator is registered for '" +
                           to_string(estimator) + "'"));
    Timer         timer; // wall time, started
    ErrorEstimate estimate = entry->second(bodies,
                                           contact_solver,
                                           mu,
                                           indicator_parameters,
                                           solver_parameters,
                                           options);
    estimate.estimator     = estimator;
    estimate.wall_time     = timer.wall_time();
    return estimate;
  }



  ErrorEstimate
  estimate_error(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolution                    *contact,
                 const double                              mu,
                 const StressRecoveryMethod                recovery,
                 const parameters::LinearSolver           &solver_parameters,
                 const ErrorEstimateOptions               &options)
  {
    ErrorEstimate estimate;
    estimate.recovery    = recovery;
    estimate.estimator   = recovery == StressRecoveryMethod::spr ?
                             ErrorEstimator::spr :
                             ErrorEstimator::zz;
    estimate.has_contact = (contact != nullptr);
    if (estimate.has_contact)
      {
        {
          const OptionalTimerSection section(options.timer,
                                             "error indicator: correction");
          estimate.correction = corrected_contact_fields(
            bodies, *contact, mu, solver_parameters, options);
        }
        const OptionalTimerSection section(options.timer,
                                           "error indicator: contributions");
        estimate.contact = integrate_contact_error(contact->mortar_interface(),
                                                   estimate.correction.fields,
                                                   mu);
      }
    else
      estimate.correction.fe_displacement = {
        {&bodies[0]->solution(), &bodies[1]->solution()}};

    std::array<double, 2> volume_squared;
    double                normalisation_squared = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        // sigma_c at the quadrature points, shared by the ZZ projection
        // and the volume terms.
        std::unique_ptr<const QuadratureStress> raw_stress;
        {
          const OptionalTimerSection section(options.timer,
                                             "error indicator: smoothing");
          raw_stress = std::make_unique<const QuadratureStress>(
            *bodies[b], estimate.correction.displacement(b));
          estimate.recovered[b] = std::make_unique<RecoveredStress>(*bodies[b]);
          estimate.recovered[b]->recover(*raw_stress, recovery);
        }
        const OptionalTimerSection section(options.timer,
                                           "error indicator: contributions");
        normalisation_squared += volume_terms(*raw_stress,
                                              *estimate.recovered[b],
                                              estimate.contribution_squared[b]);
        volume_squared[b] =
          Utilities::MPI::sum(estimate.contribution_squared[b].l1_norm(),
                              bodies[b]->triangulation().get_communicator());
      }

    const OptionalTimerSection section(options.timer,
                                       "error indicator: contributions");
    finish_error_estimate(bodies,
                          volume_squared,
                          normalisation_squared,
                          estimate);
    return estimate;
  }
} // namespace coulomb_adapt
