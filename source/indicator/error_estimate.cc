#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/indicator/error_estimate.h>

#include <cmath>

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
    volume_terms(const ElasticBody &                  body,
                 const TrilinosWrappers::MPI::Vector &displacement,
                 const RecoveredStress &              recovered,
                 Vector<double> &                     difference)
    {
      const Quadrature<2> &quadrature = body.cell_quadrature();
      FEValues<2> stress_values(body.mapping(),
                                recovered.dof_handler().get_fe(),
                                quadrature,
                                update_values | update_JxW_values);
      FEValues<2> displacement_values(body.mapping(),
                                      body.dof_handler().get_fe(),
                                      quadrature,
                                      update_gradients);
      const FEValuesExtractors::Vector   u(0);
      std::vector<SymmetricTensor<2, 2>> strains(quadrature.size());
      std::vector<Vector<double>>        smoothed(quadrature.size(),
                                           Vector<double>(3));
      const ElasticMaterial &            material = body.material();

      difference.reinit(body.triangulation().n_active_cells());
      double sum_norm = 0;
      for (const auto &cell : recovered.dof_handler().active_cell_iterators())
        {
          if (cell->is_locally_owned())
            {
              // The same cell in the displacement's DoFHandler.
              const DoFHandler<2>::active_cell_iterator displacement_cell(
                &body.triangulation(),
                cell->level(),
                cell->index(),
                &body.dof_handler());
              stress_values.reinit(cell);
              displacement_values.reinit(displacement_cell);
              displacement_values[u].get_function_symmetric_gradients(
                displacement, strains);
              stress_values.get_function_values(recovered.values(), smoothed);
              double cell_difference = 0;
              for (const unsigned int q :
                   stress_values.quadrature_point_indices())
                {
                  const SymmetricTensor<2, 2> sigma_c =
                    material.stress(strains[q]);
                  const SymmetricTensor<2, 2> sigma_s = stress_tensor(
                    Tensor<1, 3>({smoothed[q][0], smoothed[q][1], smoothed[q][2]}));
                  const SymmetricTensor<2, 2> minus = sigma_s - sigma_c;
                  const SymmetricTensor<2, 2> plus  = sigma_s + sigma_c;
                  const double                JxW   = stress_values.JxW(q);
                  cell_difference += minus * material.strain(minus) * JxW;
                  sum_norm += plus * material.strain(plus) * JxW;
                }
              difference(cell->active_cell_index()) = cell_difference;
            }
        }
      return Utilities::MPI::sum(sum_norm,
                                 body.triangulation().get_communicator());
    }
  } // namespace



  ErrorEstimate
  estimate_error(const std::array<const ElasticBody *, 2> &bodies,
                 const ContactSolver *                     contact_solver,
                 const double                              mu,
                 const StressRecoveryMethod                recovery,
                 const parameters::LinearSolver &          solver_parameters)
  {
    ErrorEstimate estimate;
    estimate.recovery    = recovery;
    estimate.has_contact = (contact_solver != nullptr);
    if (estimate.has_contact)
      {
        estimate.correction = correct_contact_solution(*bodies[0],
                                                       *bodies[1],
                                                       *contact_solver,
                                                       mu,
                                                       solver_parameters);
        estimate.contact =
          integrate_contact_error(contact_solver->mortar_interface(),
                                  estimate.correction.fields,
                                  mu);
      }
    else
      estimate.correction.fe_displacement = {{&bodies[0]->solution(),
                                             &bodies[1]->solution()}};

    std::array<double, 2> volume_squared;
    double                normalisation_squared = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        estimate.recovered[b] = std::make_unique<RecoveredStress>(*bodies[b]);
        estimate.recovered[b]->recover(estimate.correction.displacement(b),
                                       recovery);
        normalisation_squared +=
          volume_terms(*bodies[b],
                       estimate.correction.displacement(b),
                       *estimate.recovered[b],
                       estimate.contribution_squared[b]);
        volume_squared[b] = Utilities::MPI::sum(
          estimate.contribution_squared[b].l1_norm(),
          bodies[b]->triangulation().get_communicator());
      }

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
        for (const auto &cell : bodies[b]->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const auto   i  = cell->active_cell_index();
              const double e2 = estimate.contribution_squared[b](i) / D2;
              estimate.indicator[b](i) = std::sqrt(std::max(0., e2));
              estimate.density[b](i)   = e2 / cell->measure();
            }
      }
    return estimate;
  }
} // namespace coulomb_adapt
