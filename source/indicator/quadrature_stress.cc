#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/indicator/quadrature_stress.h>
#include <coulomb_adapt/indicator/recovered_stress.h>

namespace coulomb_adapt
{
  QuadratureStress::QuadratureStress(
    const ElasticBody &                  body,
    const TrilinosWrappers::MPI::Vector &displacement)
    : body_(body)
    , displacement_(displacement)
    , n_points_(body.cell_quadrature().size())
  {
    // An upper bound: the owned cells are a part of the active ones.
    stresses.reserve(body.triangulation().n_active_cells() * n_points_);
    weights.reserve(body.triangulation().n_active_cells() * n_points_);

    FEValues<2> fe_values(body.mapping(),
                          body.dof_handler().get_fe(),
                          body.cell_quadrature(),
                          update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector   u(0);
    std::vector<SymmetricTensor<2, 2>> strains(n_points_);
    for (const auto &cell : body.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_symmetric_gradients(displacement, strains);
          for (unsigned int q = 0; q < n_points_; ++q)
            {
              stresses.push_back(
                stress_components(body.material().stress(strains[q])));
              weights.push_back(fe_values.JxW(q));
            }
        }
  }



  const ElasticBody &
  QuadratureStress::body() const
  {
    return body_;
  }



  const TrilinosWrappers::MPI::Vector &
  QuadratureStress::displacement() const
  {
    return displacement_;
  }



  unsigned int
  QuadratureStress::n_points() const
  {
    return n_points_;
  }



  const Tensor<1, 3> &
  QuadratureStress::stress(const unsigned int cell, const unsigned int q) const
  {
    AssertIndexRange(cell * n_points_ + q, stresses.size());
    return stresses[cell * n_points_ + q];
  }



  double
  QuadratureStress::JxW(const unsigned int cell, const unsigned int q) const
  {
    AssertIndexRange(cell * n_points_ + q, weights.size());
    return weights[cell * n_points_ + q];
  }
} // namespace coulomb_adapt
