#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_poly.h>

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <coulomb_adapt/indicator/element_mass_operator.h>
#include <coulomb_adapt/indicator/recovered_stress.h>

#include <algorithm>
#include <array>

namespace coulomb_adapt
{
  namespace
  {
    constexpr unsigned int max_dofs_per_cell =
      ElementMassOperator::max_dofs_per_cell;
  } // namespace



  std::string
  to_string(const StressRecoveryMethod method)
  {
    return method == StressRecoveryMethod::spr ? "spr" : "zz";
  }



  RecoveredStress::RecoveredStress(const ElasticBody &body)
    : body(body)
    , fe(body.dof_handler().get_fe().base_element(0))
    , dofs(body.triangulation())
  {
    AssertThrow(fe.n_dofs_per_cell() <= max_dofs_per_cell,
                ExcMessage("The recovered stress supports up to " +
                           std::to_string(max_dofs_per_cell) +
                           " nodes per cell (Q3), not " +
                           std::to_string(fe.n_dofs_per_cell()) + "."));
    // shape_values below holds reference values: right for the scalar
    // polynomial elements (FE_Q, FE_SimplexP: FE_Poly), whose values need
    // no mapping data.
    AssertThrow(dynamic_cast<const FE_Poly<2> *>(&fe) != nullptr,
                ExcMessage("The recovered stress needs a scalar polynomial "
                           "element (FE_Q, FE_SimplexP), whose shape values "
                           "do not depend on the cell, not " +
                           fe.get_name() + "."));
    dofs.distribute_dofs(fe);
    owned_dofs = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, relevant_dofs);
    constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    constraints.close();
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      owned_dofs, relevant_dofs, body.triangulation().get_communicator());
    for (auto &c : components)
      c.reinit(partitioner);

    const Quadrature<2> &quadrature = body.cell_quadrature();
    shape_values.reinit(fe.n_dofs_per_cell(), quadrature.size());
    for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        shape_values(k, q) = fe.shape_value(k, quadrature.point(q));
  }



  void
  RecoveredStress::recover(const QuadratureStress    &raw_stress,
                           const StressRecoveryMethod method)
  {
    Assert(&raw_stress.body() == &body,
           ExcMessage("The raw stress belongs to another body."));
    if (method == StressRecoveryMethod::spr)
      recover_spr(raw_stress.displacement());
    else
      project_l2(raw_stress);
  }



  // ZZ1: minimise int (sigma~ - sigma_c)^2 over the continuous space, the
  // mass system M s_k = b_k for each component k. The components share M,
  // which is kept element by element (ElementMassOperator) from the weights
  // of @p raw_stress; the right-hand sides integrate its stresses. No
  // FEValues, sparsity pattern or assembled matrix is needed. The mass
  // matrix is spectrally equivalent to its diagonal on any shape-regular
  // mesh, graded or not: CG with Jacobi converges in a number of steps
  // independent of the mesh size.
  void
  RecoveredStress::project_l2(const QuadratureStress &raw_stress)
  {
    using BlockVectorType = ElementMassOperator::BlockVectorType;
    const ElementMassOperator mass(
      dofs, constraints, partitioner, shape_values, raw_stress);

    BlockVectorType rhs;
    mass.initialize_dof_vector(rhs);
    const unsigned int n_dofs   = fe.n_dofs_per_cell();
    const unsigned int n_points = raw_stress.n_points();
    AssertDimension(n_points, shape_values.n());
    std::array<std::array<double, max_dofs_per_cell>,
               ElementMassOperator::n_blocks>
      cell_rhs;
    for (unsigned int cell = 0; cell < raw_stress.n_cells(); ++cell)
      {
        for (auto &r : cell_rhs)
          std::fill(r.begin(), r.begin() + n_dofs, 0.);
        for (unsigned int q = 0; q < n_points; ++q)
          {
            const Tensor<1, 3> &sigma = raw_stress.stress(cell, q);
            const double        JxW   = raw_stress.JxW(cell, q);
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const double phi_i = shape_values(i, q) * JxW;
                for (unsigned int c = 0; c < 3; ++c)
                  cell_rhs[c][i] += phi_i * sigma[c];
              }
          }
        for (unsigned int c = 0; c < ElementMassOperator::n_blocks; ++c)
          mass.distribute_local_to_global(
            cell,
            make_array_view(cell_rhs[c].begin(), cell_rhs[c].begin() + n_dofs),
            rhs.block(c));
      }
    rhs.compress(VectorOperation::add);

    BlockVectorType solution;
    mass.initialize_dof_vector(solution);
    // A zero stress (an unloaded body) has nothing to solve for.
    if (rhs.linfty_norm() > 0)
      {
        // Relative to the right-hand side of all three components: the
        // indicator measures sigma~ in a norm of the whole stress.
        SolverControl             control(1000, 1e-12 * rhs.l2_norm());
        SolverCG<BlockVectorType> cg(control);
        PreconditionJacobi<ElementMassOperator> jacobi;
        jacobi.initialize(mass);
        cg.solve(mass, solution, rhs, jacobi);
      }

    for (unsigned int c = 0; c < 3; ++c)
      {
        // The same partitioner: take the solution over without a copy.
        components[c].swap(solution.block(c));
        constraints.distribute(components[c]);
        components[c].update_ghost_values();
      }
  }



  void
  RecoveredStress::get_quadrature_values(
    const DoFHandler<2>::active_cell_iterator &cell,
    std::vector<Tensor<1, 3>>                 &values) const
  {
    const unsigned int n_dofs = fe.n_dofs_per_cell();
    values.assign(shape_values.n(), Tensor<1, 3>());
    // On the stack: this runs once per cell.
    std::array<double, max_dofs_per_cell> nodal;
    for (unsigned int c = 0; c < 3; ++c)
      {
        cell->get_dof_values(components[c],
                             nodal.begin(),
                             nodal.begin() + n_dofs);
        for (unsigned int q = 0; q < shape_values.n(); ++q)
          for (unsigned int k = 0; k < n_dofs; ++k)
            values[q][c] += shape_values(k, q) * nodal[k];
      }
  }



  const DoFHandler<2> &
  RecoveredStress::dof_handler() const
  {
    return dofs;
  }



  const RecoveredStress::VectorType &
  RecoveredStress::component(const unsigned int c) const
  {
    AssertIndexRange(c, 3);
    return components[c];
  }

} // namespace coulomb_adapt
