#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_poly.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/indicator/recovered_stress.h>

#include <array>

namespace coulomb_adapt
{
  namespace
  {
    // Nodes per cell of a Q3 element: more than the degrees the program
    // offers (1 and 2).
    constexpr unsigned int max_dofs_per_cell = 16;
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
    for (auto &c : components)
      c.reinit(owned_dofs, relevant_dofs, body.triangulation().get_communicator());

    const Quadrature<2> &quadrature = body.cell_quadrature();
    shape_values.reinit(fe.n_dofs_per_cell(), quadrature.size());
    for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        shape_values(k, q) = fe.shape_value(k, quadrature.point(q));
  }



  void
  RecoveredStress::recover(const QuadratureStress &   raw_stress,
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
  // so M is assembled once on the scalar space and solved for three
  // right-hand sides. Both integrals use the points and weights of
  // @p raw_stress, so no FEValues is needed here. The mass matrix is
  // spectrally equivalent to its diagonal on any shape-regular mesh, graded
  // or not: CG with Jacobi converges in a number of steps independent of
  // the mesh size. deal.II's CG on the Trilinos matrix and vectors: the
  // same parallel solve without AztecOO's set-up per call, which matters on
  // the small meshes.
  void
  RecoveredStress::project_l2(const QuadratureStress &raw_stress)
  {
    const MPI_Comm comm = body.triangulation().get_communicator();
    DynamicSparsityPattern dsp(relevant_dofs);
    DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               owned_dofs,
                                               comm,
                                               relevant_dofs);
    TrilinosWrappers::SparseMatrix mass;
    mass.reinit(owned_dofs, owned_dofs, dsp, comm);
    std::array<TrilinosWrappers::MPI::Vector, 3> rhs;
    for (auto &r : rhs)
      r.reinit(owned_dofs, comm);

    const unsigned int                   n_dofs   = fe.n_dofs_per_cell();
    const unsigned int                   n_points = raw_stress.n_points();
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    // The right-hand sides are summed per locally relevant DoF first and
    // handed to Trilinos (through the hanging-node constraints) once at
    // the end: one Epetra insertion per DoF instead of one per cell and
    // DoF, which was a third of the assembly on small meshes.
    std::array<Vector<double>, 3> relevant_rhs;
    for (auto &r : relevant_rhs)
      r.reinit(relevant_dofs.n_elements());
    std::array<unsigned int, max_dofs_per_cell> relevant_index;

    AssertDimension(n_points, shape_values.n());
    unsigned int owned_cell = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < n_dofs; ++i)
            relevant_index[i] = relevant_dofs.index_within_set(dof_indices[i]);
          cell_matrix = 0;
          for (unsigned int q = 0; q < n_points; ++q)
            {
              const Tensor<1, 3> &sigma = raw_stress.stress(owned_cell, q);
              const double        JxW   = raw_stress.JxW(owned_cell, q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const double phi_i = shape_values(i, q) * JxW;
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += phi_i * shape_values(j, q);
                  for (unsigned int c = 0; c < 3; ++c)
                    relevant_rhs[c](relevant_index[i]) += phi_i * sigma[c];
                }
            }
          ++owned_cell;
          constraints.distribute_local_to_global(cell_matrix,
                                                 dof_indices,
                                                 mass);
        }
    AssertDimension(owned_cell, raw_stress.n_cells());
    std::vector<types::global_dof_index> relevant_indices;
    relevant_dofs.fill_index_vector(relevant_indices);
    for (unsigned int c = 0; c < 3; ++c)
      constraints.distribute_local_to_global(relevant_rhs[c],
                                             relevant_indices,
                                             rhs[c]);
    mass.compress(VectorOperation::add);
    for (auto &r : rhs)
      r.compress(VectorOperation::add);

    TrilinosWrappers::PreconditionJacobi jacobi;
    jacobi.initialize(mass);
    for (unsigned int c = 0; c < 3; ++c)
      {
        TrilinosWrappers::MPI::Vector solution(owned_dofs, comm);
        // A component that vanishes identically (sigma_xy of a uniform
        // pressure) has nothing to solve for.
        if (rhs[c].linfty_norm() > 0)
          {
            SolverControl control(1000, 1e-12 * rhs[c].l2_norm());
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            cg.solve(mass, solution, rhs[c], jacobi);
          }
        constraints.distribute(solution);
        components[c] = solution;
      }
  }



  void
  RecoveredStress::get_quadrature_values(
    const DoFHandler<2>::active_cell_iterator &cell,
    std::vector<Tensor<1, 3>> &                values) const
  {
    const unsigned int n_dofs = fe.n_dofs_per_cell();
    values.assign(shape_values.n(), Tensor<1, 3>());
    // On the stack: this runs once per cell.
    std::array<double, max_dofs_per_cell> nodal;
    for (unsigned int c = 0; c < 3; ++c)
      {
        cell->get_dof_values(components[c], nodal.begin(), nodal.begin() + n_dofs);
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



  const TrilinosWrappers::MPI::Vector &
  RecoveredStress::component(const unsigned int c) const
  {
    AssertIndexRange(c, 3);
    return components[c];
  }

} // namespace coulomb_adapt
