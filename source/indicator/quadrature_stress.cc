#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/indicator/quadrature_stress.h>

#include <utility>

namespace coulomb_adapt
{
  QuadratureStress::QuadratureStress(
    const ElasticBody                   &body,
    const TrilinosWrappers::MPI::Vector &displacement)
    : QuadratureStress(body, displacement, body.cell_quadrature(), false)
  {}



  QuadratureStress::QuadratureStress(
    const ElasticBody                   &body,
    const TrilinosWrappers::MPI::Vector &displacement,
    const Quadrature<2>                 &quadrature,
    const bool                           with_points)
    : body_(body)
    , displacement_(displacement)
    , n_points_(quadrature.size())
  {
    // An upper bound: the owned cells are a part of the active ones.
    stresses.reserve(body.triangulation().n_active_cells() * n_points_);
    weights.reserve(body.triangulation().n_active_cells() * n_points_);

    // FEValues of the scalar base element: the displacement element is
    // FESystem(base, 2), and its shape gradients are those of the base
    // copied per component, work that the strain does not need.
    const FiniteElement<2> &displacement_fe = body.dof_handler().get_fe();
    const FiniteElement<2> &base            = displacement_fe.base_element(0);
    FEValues<2>             fe_values(body.mapping(),
                          base,
                          quadrature,
                          update_gradients | update_JxW_values |
                            (with_points ? update_quadrature_points :
                                                       update_default));
    if (with_points)
      points.reserve(body.triangulation().n_active_cells() * n_points_);
    const unsigned int n_dofs = displacement_fe.n_dofs_per_cell();
    std::vector<std::pair<unsigned int, unsigned int>> component_node(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component_node[i] = displacement_fe.system_to_component_index(i);
    Vector<double> nodal(n_dofs);
    for (const auto &cell : body.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(static_cast<Triangulation<2>::cell_iterator>(cell));
          cell->get_dof_values(displacement, nodal);
          for (unsigned int q = 0; q < n_points_; ++q)
            {
              Tensor<2, 2> gradient;
              for (unsigned int i = 0; i < n_dofs; ++i)
                gradient[component_node[i].first] +=
                  nodal[i] * fe_values.shape_grad(component_node[i].second, q);
              stresses.push_back(stress_components(
                body.material().stress(symmetrize(gradient))));
              weights.push_back(fe_values.JxW(q));
              if (with_points)
                points.push_back(fe_values.quadrature_point(q));
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



  unsigned int
  QuadratureStress::n_cells() const
  {
    return n_points_ > 0 ? weights.size() / n_points_ : 0;
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



  const Point<2> &
  QuadratureStress::point(const unsigned int cell, const unsigned int q) const
  {
    Assert(!points.empty() || weights.empty(),
           ExcMessage("Constructed without the points' positions."));
    AssertIndexRange(cell * n_points_ + q, points.size());
    return points[cell * n_points_ + q];
  }
} // namespace coulomb_adapt
