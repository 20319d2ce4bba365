#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/vector_tools_evaluate.h>

#include <deal.II/hp/fe_collection.h>
#include <deal.II/hp/fe_values.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/indicator/exact_error.h>

#include <algorithm>
#include <cmath>

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
  // (see compare_with_exact_error) suffices.
  unsigned int
  ExactSolutionStress::quadrature_subdivisions(const unsigned int,
                                               const double) const
  {
    return 1;
  }



  std::string
  ExactSolutionStress::description() const
  {
    return "exact solution";
  }



  ReferenceSolutionStress::ReferenceSolutionStress(
    const MPI_Comm     mpi_communicator,
    const Scene &      scene,
    const Parameters & parameters,
    const unsigned int global_refinements,
    const unsigned int reference_refinements,
    const bool         for_adapted_meshes)
    : quiet(std::cout, false)
    , reference_refinements(reference_refinements)
    , for_adapted_meshes(for_adapted_meshes)
  {
    for (unsigned int b = 0; b < 2; ++b)
      {
        bodies[b] = std::make_unique<ElasticBody>(mpi_communicator,
                                                  scene,
                                                  b,
                                                  parameters.mesh.cell_type,
                                                  global_refinements +
                                                    reference_refinements,
                                                  parameters.finite_elements);
        bodies[b]->setup_system();
        bodies[b]->assemble_system();
      }
    contact_solver = std::make_unique<ContactSolver>(*bodies[0],
                                                     *bodies[1],
                                                     parameters.contact,
                                                     parameters.linear_solver,
                                                     quiet);
    n_newton_iterations = contact_solver->solve().newton_iterations;
    for (unsigned int b = 0; b < 2; ++b)
      {
        double largest = 0;
        for (const auto &cell : bodies[b]->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            largest = std::max(largest, cell->diameter());
        largest_cell_diameter[b] =
          Utilities::MPI::max(largest, mpi_communicator);
      }
  }



  ReferenceSolutionStress::~ReferenceSolutionStress() = default;



  std::vector<SymmetricTensor<2, 2>>
  ReferenceSolutionStress::stresses(const unsigned int           b,
                                    const std::vector<Point<2>> &points) const
  {
    const ElasticBody &                   body = *bodies[b];
    Utilities::MPI::RemotePointEvaluation<2> evaluation(1e-10);
    const auto gradients = VectorTools::point_gradients<2>(
      body.mapping(), body.dof_handler(), body.solution(), points, evaluation);
    AssertThrow(evaluation.all_points_found(),
                ExcMessage("Some evaluation points of body '" + body.name() +
                           "' lie outside the reference mesh."));
    std::vector<SymmetricTensor<2, 2>> sigma(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        Tensor<2, 2> gradient;
        for (unsigned int c = 0; c < 2; ++c)
          gradient[c] = gradients[i][c];
        sigma[i] = body.material().stress(symmetrize(gradient));
      }
    return sigma;
  }



  unsigned int
  ReferenceSolutionStress::quadrature_subdivisions(
    const unsigned int b,
    const double       cell_diameter) const
  {
    const unsigned int uniform = 1u << reference_refinements;
    if (!for_adapted_meshes)
      return uniform;
    const double fit = std::ceil(cell_diameter / largest_cell_diameter[b] - 1e-8);
    return std::clamp(static_cast<unsigned int>(std::max(fit, 1.)), 1u, uniform);
  }



  std::string
  ReferenceSolutionStress::description() const
  {
    return "reference solution (" +
           std::to_string(bodies[0]->dof_handler().n_dofs() +
                          bodies[1]->dof_handler().n_dofs()) +
           " DoFs)";
  }



  unsigned int
  ReferenceSolutionStress::newton_iterations() const
  {
    return n_newton_iterations;
  }



  ExactErrorComparison
  compare_with_exact_error(const std::array<const ElasticBody *, 2> &bodies,
                           const ErrorEstimate &                     estimate,
                           const ReferenceStress &                   reference)
  {
    const MPI_Comm comm = bodies[0]->triangulation().get_communicator();
    std::array<Vector<double>, 2> exact_squared;
    double                        sum_minus = 0, sum_plus = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const ElasticBody &body   = *bodies[b];
        const unsigned int degree = body.dof_handler().get_fe().degree;
        // A piecewise reference field on n x n sub-cells: the iterated
        // rule integrates each piece on its own. n varies from cell to
        // cell on adapted meshes: hp::FEValues selects the rule (entry
        // n - 1 of the collection) per cell.
        std::vector<unsigned int> subdivisions;
        for (const auto &cell : body.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            subdivisions.push_back(
              reference.quadrature_subdivisions(b, cell->diameter()));
        const unsigned int max_subdivisions =
          subdivisions.empty() ?
            1 :
            *std::max_element(subdivisions.begin(), subdivisions.end());
        hp::QCollection<2> quadratures;
        for (unsigned int n = 1; n <= max_subdivisions; ++n)
          if (body.is_simplex_mesh())
            quadratures.push_back(QIteratedSimplex<2>(
              QGaussSimplex<2>(std::min(degree + 2, 4u)), n));
          else
            quadratures.push_back(QIterated<2>(QGauss<1>(degree + 2), n));
        const hp::MappingCollection<2> mappings(body.mapping());
        const hp::FECollection<2>      elements(body.dof_handler().get_fe());
        hp::FEValues<2>                hp_fe_values(mappings,
                                     elements,
                                     quadratures,
                                     update_gradients |
                                       update_quadrature_points |
                                       update_JxW_values);
        const FEValuesExtractors::Vector u(0);
        std::vector<SymmetricTensor<2, 2>> strains;

        // All points of the locally owned cells, then one collective
        // evaluation of the reference.
        std::vector<Point<2>>              points;
        std::vector<SymmetricTensor<2, 2>> sigma_c;
        std::vector<double>                JxW;
        std::vector<unsigned int>          cell_of_point;
        unsigned int owned_cell = 0;
        for (const auto &cell : body.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              hp_fe_values.reinit(cell, subdivisions[owned_cell++] - 1);
              const FEValues<2> &fe_values =
                hp_fe_values.get_present_fe_values();
              strains.resize(fe_values.n_quadrature_points);
              fe_values[u].get_function_symmetric_gradients(
                estimate.correction.displacement(b), strains);
              for (const unsigned int q : fe_values.quadrature_point_indices())
                {
                  points.push_back(fe_values.quadrature_point(q));
                  sigma_c.push_back(body.material().stress(strains[q]));
                  JxW.push_back(fe_values.JxW(q));
                  cell_of_point.push_back(cell->active_cell_index());
                }
            }
        const auto sigma = reference.stresses(b, points);

        exact_squared[b].reinit(body.triangulation().n_active_cells());
        for (unsigned int i = 0; i < points.size(); ++i)
          {
            const SymmetricTensor<2, 2> minus = sigma[i] - sigma_c[i];
            const SymmetricTensor<2, 2> plus  = sigma[i] + sigma_c[i];
            exact_squared[b](cell_of_point[i]) +=
              minus * body.material().strain(minus) * JxW[i];
            sum_minus += minus * body.material().strain(minus) * JxW[i];
            sum_plus += plus * body.material().strain(plus) * JxW[i];
          }
      }
    sum_minus = Utilities::MPI::sum(sum_minus, comm);
    sum_plus  = Utilities::MPI::sum(sum_plus, comm);

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
    comparison.effectivity =
      comparison.epsilon_exact > 0 ? estimate.epsilon / comparison.epsilon_exact :
                                     0.;

    double largest = 0;
    for (unsigned int b = 0; b < 2; ++b)
      largest = std::max(largest, exact_squared[b].linfty_norm());
    largest = Utilities::MPI::max(largest, comm);
    double       sum = 0, sum_squares = 0;
    double       low = 1e300, high = 0;
    unsigned int n   = 0;
    for (unsigned int b = 0; b < 2; ++b)
      for (const auto &cell : bodies[b]->triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto i = cell->active_cell_index();
            if (exact_squared[b](i) <= 1e-12 * largest)
              continue;
            const double theta = std::sqrt(
              std::max(0., estimate.contribution_squared[b](i)) /
              exact_squared[b](i));
            sum += theta;
            sum_squares += theta * theta;
            low  = std::min(low, theta);
            high = std::max(high, theta);
            ++n;
          }
    n           = Utilities::MPI::sum(n, comm);
    sum         = Utilities::MPI::sum(sum, comm);
    sum_squares = Utilities::MPI::sum(sum_squares, comm);
    comparison.n_elements = n;
    if (n > 0)
      {
        comparison.element_effectivity_mean = sum / n;
        comparison.element_effectivity_std  = std::sqrt(
          std::max(0., sum_squares / n - std::pow(sum / n, 2)));
        comparison.element_effectivity_min = Utilities::MPI::min(low, comm);
        comparison.element_effectivity_max = Utilities::MPI::max(high, comm);
      }
    return comparison;
  }
} // namespace coulomb_adapt
