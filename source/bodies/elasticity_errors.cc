#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/bodies/elasticity_errors.h>

#include <cmath>

namespace coulomb_adapt
{
  ElasticityErrors
  compute_elasticity_errors(const ElasticBody &body, const Function<2> &exact)
  {
    const auto &fe = body.dof_handler().get_fe();
    // QGaussSimplex offers at most 4 points per direction in deal.II 9.4.
    const unsigned int n_q_1d =
      body.is_simplex_mesh() ? std::min(fe.degree + 2, 4u) : fe.degree + 3;
    std::unique_ptr<Quadrature<2>> quadrature;
    if (body.is_simplex_mesh())
      quadrature = std::make_unique<QGaussSimplex<2>>(n_q_1d);
    else
      quadrature = std::make_unique<QGauss<2>>(n_q_1d);

    FEValues<2>                        fe_values(body.mapping(),
                          fe,
                          *quadrature,
                          update_values | update_gradients |
                            update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector   u(0);
    std::vector<Tensor<1, 2>>          values(quadrature->size());
    std::vector<SymmetricTensor<2, 2>> strains(quadrature->size());
    const ElasticMaterial             &material = body.material();

    double l2_squared = 0, energy_squared = 0, exact_energy_squared = 0;
    for (const auto &cell : body.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_values(body.solution(), values);
          fe_values[u].get_function_symmetric_gradients(body.solution(),
                                                        strains);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Point<2> &x = fe_values.quadrature_point(q);
              Tensor<1, 2>    exact_value;
              Tensor<2, 2>    exact_gradient;
              for (unsigned int c = 0; c < 2; ++c)
                {
                  exact_value[c]    = exact.value(x, c);
                  exact_gradient[c] = exact.gradient(x, c);
                }
              const SymmetricTensor<2, 2> exact_strain =
                symmetrize(exact_gradient);
              const SymmetricTensor<2, 2> strain_error =
                strains[q] - exact_strain;
              const double JxW = fe_values.JxW(q);
              l2_squared += (values[q] - exact_value).norm_square() * JxW;
              energy_squared +=
                material.stress(strain_error) * strain_error * JxW;
              exact_energy_squared +=
                material.stress(exact_strain) * exact_strain * JxW;
            }
        }
    const MPI_Comm comm = body.triangulation().get_communicator();
    return {std::sqrt(Utilities::MPI::sum(l2_squared, comm)),
            std::sqrt(Utilities::MPI::sum(energy_squared, comm)),
            std::sqrt(Utilities::MPI::sum(exact_energy_squared, comm))};
  }
} // namespace coulomb_adapt
