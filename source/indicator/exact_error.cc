#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/filtered_iterator.h>

#include <deal.II/numerics/vector_tools_evaluate.h>

#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/indicator/exact_error.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

namespace coulomb_adapt
{
  ExactSolutionStress::ExactSolutionStress(
    const std::array<const ElasticBody *, 2> &bodies)
    : bodies(bodies)
  {
    for (const auto *body : bodies)
      AssertThrow(body->description().exact_displacement,
                  ExcMessage("Body '" + body->name() +
                             "' has no exact solution."));
  }



  std::vector<SymmetricTensor<2, 2>>
  ExactSolutionStress::stresses(const unsigned int           b,
                                const std::vector<Point<2>> &points) const
  {
    const Function<2> &exact = *bodies[b]->description().exact_displacement;
    std::vector<SymmetricTensor<2, 2>> sigma(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        Tensor<2, 2> gradient;
        for (unsigned int c = 0; c < 2; ++c)
          gradient[c] = exact.gradient(points[i], c);
        sigma[i] = bodies[b]->material().stress(symmetrize(gradient));
      }
    return sigma;
  }



  // The exact stress is smooth: one subdivision with a higher-order rule
  // (see compare_stresses) suffices.
  unsigned int
  ExactSolutionStress::quadrature_subdivisions() const
  {
    return 1;
  }



  std::string
  ExactSolutionStress::description() const
  {
    return "exact solution";
  }



  // The cells on the threads deal.II may use (WorkStream), their energies
  // added in the cells' order: the same sum as a serial loop up to the
  // round-off of FEValues' reuse of a translated previous cell's geometry.
  // Every run computes it for every cycle (summary.json's strain_energy):
  // serially it took 0.07 s on the last mesh of blocks at epsilon_0 =
  // 0.25 % (162,788 DoFs), now 0.05 s (benchmarks/adaptive_run).
  double
  strain_energy(const ElasticBody                   &body,
                const TrilinosWrappers::MPI::Vector &displacement)
  {
    struct Scratch
    {
      explicit Scratch(const ElasticBody &body)
        : fe_values(body.mapping(),
                    body.dof_handler().get_fe(),
                    body.cell_quadrature(),
                    update_gradients | update_JxW_values)
        , strains(body.cell_quadrature().size())
      {}
      Scratch(const Scratch &other)
        : fe_values(other.fe_values.get_mapping(),
                    other.fe_values.get_fe(),
                    other.fe_values.get_quadrature(),
                    other.fe_values.get_update_flags())
        , strains(other.strains.size())
      {}
      FEValues<2>                        fe_values;
      std::vector<SymmetricTensor<2, 2>> strains;
    };
    const FEValuesExtractors::Vector u(0);
    double                           energy = 0;
    using OwnedCell = FilteredIterator<DoFHandler<2>::active_cell_iterator>;
    const DoFHandler<2> &dofs = body.dof_handler();
    WorkStream::run(
      OwnedCell(IteratorFilters::LocallyOwnedCell(), dofs.begin_active()),
      OwnedCell(IteratorFilters::LocallyOwnedCell(), dofs.end()),
      [&](const OwnedCell &cell, Scratch &scratch, double &cell_energy) {
        scratch.fe_values.reinit(cell);
        scratch.fe_values[u].get_function_symmetric_gradients(displacement,
                                                              scratch.strains);
        cell_energy = 0;
        for (const unsigned int q :
             scratch.fe_values.quadrature_point_indices())
          cell_energy += 0.5 * body.material().stress(scratch.strains[q]) *
                         scratch.strains[q] * scratch.fe_values.JxW(q);
      },
      [&](const double &cell_energy) { energy += cell_energy; },
      Scratch(body),
      0.);
    return Utilities::MPI::sum(energy, body.triangulation().get_communicator());
  }



  StressDifference
  compare_stresses(
    const std::array<const ElasticBody *, 2>                   &bodies,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements,
    const ReferenceStress                                      &reference,
    const unsigned int                                          subdivisions)
  {
    StressDifference result;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const ElasticBody &body   = *bodies[b];
        const unsigned int degree = body.dof_handler().get_fe().degree;
        // A piecewise reference field on n x n sub-cells: the iterated
        // rule integrates each piece on its own.
        const Quadrature<2> quadrature =
          body.is_simplex_mesh() ?
            Quadrature<2>(
              QIteratedSimplex<2>(QGaussSimplex<2>(std::min(degree + 2, 4u)),
                                  subdivisions)) :
            Quadrature<2>(QIterated<2>(QGauss<1>(degree + 2), subdivisions));
        FEValues<2>                        fe_values(body.mapping(),
                              body.dof_handler().get_fe(),
                              quadrature,
                              update_gradients | update_quadrature_points |
                                update_JxW_values);
        const FEValuesExtractors::Vector   u(0);
        std::vector<SymmetricTensor<2, 2>> strains(quadrature.size());

        // All points of the locally owned cells, then one collective
        // evaluation of the reference.
        std::vector<Point<2>>              points;
        std::vector<SymmetricTensor<2, 2>> sigma_h;
        std::vector<double>                JxW;
        std::vector<unsigned int>          cell_of_point;
        for (const auto &cell : body.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              fe_values[u].get_function_symmetric_gradients(*displacements[b],
                                                            strains);
              for (const unsigned int q : fe_values.quadrature_point_indices())
                {
                  points.push_back(fe_values.quadrature_point(q));
                  sigma_h.push_back(body.material().stress(strains[q]));
                  JxW.push_back(fe_values.JxW(q));
                  cell_of_point.push_back(cell->active_cell_index());
                }
            }
        const auto sigma = reference.stresses(b, points);

        result.cell_squared[b].reinit(body.triangulation().n_active_cells());
        for (unsigned int i = 0; i < points.size(); ++i)
          {
            const SymmetricTensor<2, 2> minus = sigma[i] - sigma_h[i];
            const SymmetricTensor<2, 2> plus  = sigma[i] + sigma_h[i];
            const double                minus_squared =
              minus * body.material().strain(minus) * JxW[i];
            result.cell_squared[b](cell_of_point[i]) += minus_squared;
            result.difference_squared += minus_squared;
            result.sum_squared += plus * body.material().strain(plus) * JxW[i];
          }
      }
    const MPI_Comm comm = bodies[0]->triangulation().get_communicator();
    result.difference_squared =
      Utilities::MPI::sum(result.difference_squared, comm);
    result.sum_squared = Utilities::MPI::sum(result.sum_squared, comm);
    return result;
  }



  ExactErrorComparison
  compare_with_exact_error(const std::array<const ElasticBody *, 2> &bodies,
                           const ErrorEstimate                      &estimate,
                           const ReferenceStress                    &reference)
  {
    const MPI_Comm   comm = bodies[0]->triangulation().get_communicator();
    StressDifference d =
      compare_stresses(bodies,
                       {{&estimate.correction.displacement(0),
                         &estimate.correction.displacement(1)}},
                       reference,
                       reference.quadrature_subdivisions());
    std::array<Vector<double>, 2> &exact_squared = d.cell_squared;
    const double                   sum_minus     = d.difference_squared;
    const double                   sum_plus      = d.sum_squared;

    // The contact term is computable: the same as in the estimate.
    const double contact = 2 * estimate.contact.integral;
    if (estimate.has_contact)
      for (unsigned int b = 0; b < 2; ++b)
        {
          const auto cells = owned_boundary_cell_indices(*bodies[b]);
          for (const auto &[id, value] :
               (b == 0 ? estimate.contact.slave_cells :
                         estimate.contact.master_cells))
            if (const auto c = cells.find(id); c != cells.end())
              exact_squared[b](c->second) += value;
        }

    ExactErrorComparison comparison;
    comparison.epsilon_exact =
      std::sqrt((sum_minus + contact) / std::max(sum_plus, 1e-300));
    comparison.effectivity = comparison.epsilon_exact > 0 ?
                               estimate.epsilon / comparison.epsilon_exact :
                               0.;

    double largest = 0;
    for (unsigned int b = 0; b < 2; ++b)
      largest = std::max(largest, exact_squared[b].linfty_norm());
    largest          = Utilities::MPI::max(largest, comm);
    double       sum = 0, sum_squares = 0;
    double       low = 1e300, high = 0;
    unsigned int n = 0;
    for (unsigned int b = 0; b < 2; ++b)
      for (const auto &cell :
           bodies[b]->triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto i = cell->active_cell_index();
            if (exact_squared[b](i) <= 1e-12 * largest)
              continue;
            const double theta =
              std::sqrt(std::max(0., estimate.contribution_squared[b](i)) /
                        exact_squared[b](i));
            sum += theta;
            sum_squares += theta * theta;
            low  = std::min(low, theta);
            high = std::max(high, theta);
            ++n;
          }
    n                     = Utilities::MPI::sum(n, comm);
    sum                   = Utilities::MPI::sum(sum, comm);
    sum_squares           = Utilities::MPI::sum(sum_squares, comm);
    comparison.n_elements = n;
    if (n > 0)
      {
        comparison.element_effectivity_mean = sum / n;
        comparison.element_effectivity_std =
          std::sqrt(std::max(0., sum_squares / n - std::pow(sum / n, 2)));
        comparison.element_effectivity_min = Utilities::MPI::min(low, comm);
        comparison.element_effectivity_max = Utilities::MPI::max(high, comm);
      }
    return comparison;
  }


  double
  extrapolated_exact_error(const double       against_reference,
                           const double       own_error,
                           const unsigned int refinements)
  {
    const double a2 = against_reference * against_reference;
    const double d2 = own_error * own_error;
    if (refinements < 2 || !(refinements * d2 < a2))
      return 0;
    // f(t) = (1 + t)^R - 1 - r t is convex with f(0) = 0 and f'(0) =
    // R - r < 0: one positive root, bracketed by doubling, then bisected.
    const double r = a2 / d2;
    const auto   f = [&](const double t) {
      return std::pow(1 + t, refinements) - 1 - r * t;
    };
    double low = 0, high = 1;
    while (f(high) < 0)
      low = high, high *= 2;
    for (unsigned int i = 0; i < 200 && high - low > 1e-15 * high; ++i)
      {
        const double middle          = (low + high) / 2;
        (f(middle) < 0 ? low : high) = middle;
      }
    return std::sqrt(a2 + d2 / high);
  }
} // namespace coulomb_adapt
