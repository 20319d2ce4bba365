#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <coulomb_adapt/indicator/recovered_stress.h>

#include <array>

namespace coulomb_adapt
{
  std::string
  to_string(const StressRecoveryMethod method)
  {
    return method == StressRecoveryMethod::spr ? "spr" : "zz";
  }



  RecoveredStress::RecoveredStress(const ElasticBody &body)
    : body(body)
    , fe(std::make_unique<FESystem<2>>(
        body.dof_handler().get_fe().base_element(0), 3))
    , dofs(body.triangulation())
  {
    dofs.distribute_dofs(*fe);
    owned_dofs = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, relevant_dofs);
    constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    constraints.close();
    recovered.reinit(owned_dofs,
                     relevant_dofs,
                     body.triangulation().get_communicator());
  }



  void
  RecoveredStress::recover(const TrilinosWrappers::MPI::Vector &displacement,
                           const StressRecoveryMethod           method)
  {
    if (method == StressRecoveryMethod::spr)
      recover_spr(displacement);
    else
      project_l2(displacement);
  }



  // ZZ1: minimise int (sigma~ - sigma_c)^2 over the continuous space, the
  // mass system M s_k = b_k for each component k. The components share M,
  // so M is assembled once, on a scalar copy of the space (a ninth of the
  // entries of the block-diagonal system matrix of the FESystem, which is
  // where the indicator spent most of its time), and solved for three
  // right-hand sides. The mass matrix is spectrally equivalent to its
  // diagonal on any shape-regular mesh, graded or not: CG with Jacobi
  // converges in a number of steps independent of the mesh size. deal.II's
  // CG on the Trilinos matrix and vectors: the same parallel solve without
  // AztecOO's set-up per call, which matters on the small meshes.
  void
  RecoveredStress::project_l2(const TrilinosWrappers::MPI::Vector &displacement)
  {
    const MPI_Comm        comm = body.triangulation().get_communicator();
    const FiniteElement<2> &scalar_fe = fe->base_element(0);
    DoFHandler<2>         scalar_dofs(body.triangulation());
    scalar_dofs.distribute_dofs(scalar_fe);
    const IndexSet scalar_owned = scalar_dofs.locally_owned_dofs();
    IndexSet       scalar_relevant;
    DoFTools::extract_locally_relevant_dofs(scalar_dofs, scalar_relevant);
    AffineConstraints<double> scalar_constraints(scalar_relevant);
    DoFTools::make_hanging_node_constraints(scalar_dofs, scalar_constraints);
    scalar_constraints.close();

    DynamicSparsityPattern dsp(scalar_relevant);
    DoFTools::make_sparsity_pattern(scalar_dofs, dsp, scalar_constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               scalar_owned,
                                               comm,
                                               scalar_relevant);
    TrilinosWrappers::SparseMatrix mass;
    mass.reinit(scalar_owned, scalar_owned, dsp, comm);
    std::array<TrilinosWrappers::MPI::Vector, 3> rhs;
    for (auto &r : rhs)
      r.reinit(scalar_owned, comm);

    const Quadrature<2> &quadrature = body.cell_quadrature();
    FEValues<2>          stress_values(body.mapping(),
                              scalar_fe,
                              quadrature,
                              update_values | update_JxW_values);
    FEValues<2>          displacement_values(body.mapping(),
                                    body.dof_handler().get_fe(),
                                    quadrature,
                                    update_gradients);
    const FEValuesExtractors::Vector     u(0);
    const unsigned int                   n_dofs = scalar_fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    std::array<Vector<double>, 3>        cell_rhs;
    for (auto &r : cell_rhs)
      r.reinit(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<SymmetricTensor<2, 2>>   strains(quadrature.size());

    for (const auto &cell : scalar_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          // The same cell in the displacement's DoFHandler.
          const DoFHandler<2>::active_cell_iterator displacement_cell(
            &body.triangulation(), cell->level(), cell->index(), &body.dof_handler());
          stress_values.reinit(cell);
          displacement_values.reinit(displacement_cell);
          displacement_values[u].get_function_symmetric_gradients(displacement,
                                                                  strains);
          cell_matrix = 0;
          for (auto &r : cell_rhs)
            r = 0;
          for (const unsigned int q : stress_values.quadrature_point_indices())
            {
              const Tensor<1, 3> sigma =
                stress_components(body.material().stress(strains[q]));
              const double JxW = stress_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const double phi_i = stress_values.shape_value(i, q) * JxW;
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += phi_i * stress_values.shape_value(j, q);
                  for (unsigned int c = 0; c < 3; ++c)
                    cell_rhs[c](i) += phi_i * sigma[c];
                }
            }
          cell->get_dof_indices(dof_indices);
          scalar_constraints.distribute_local_to_global(
            cell_matrix, cell_rhs[0], dof_indices, mass, rhs[0]);
          for (unsigned int c = 1; c < 3; ++c)
            scalar_constraints.distribute_local_to_global(cell_rhs[c],
                                                          dof_indices,
                                                          rhs[c]);
        }
    mass.compress(VectorOperation::add);
    for (auto &r : rhs)
      r.compress(VectorOperation::add);

    TrilinosWrappers::PreconditionJacobi jacobi;
    jacobi.initialize(mass);
    std::array<TrilinosWrappers::MPI::Vector, 3> component;
    for (unsigned int c = 0; c < 3; ++c)
      {
        TrilinosWrappers::MPI::Vector solution(scalar_owned, comm);
        // A component that vanishes identically (sigma_xy of a uniform
        // pressure) has nothing to solve for.
        if (rhs[c].linfty_norm() > 0)
          {
            SolverControl              control(1000, 1e-12 * rhs[c].l2_norm());
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            cg.solve(mass, solution, rhs[c], jacobi);
          }
        scalar_constraints.distribute(solution);
        component[c].reinit(scalar_owned, scalar_relevant, comm);
        component[c] = solution;
      }

    // Into the three-component stress space: local DoF i of a cell is
    // component c of the scalar DoF system_to_component_index(i).second.
    TrilinosWrappers::MPI::Vector        values(owned_dofs, comm);
    std::vector<types::global_dof_index> system_indices(fe->n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const DoFHandler<2>::active_cell_iterator scalar_cell(
            &body.triangulation(), cell->level(), cell->index(), &scalar_dofs);
          scalar_cell->get_dof_indices(dof_indices);
          cell->get_dof_indices(system_indices);
          for (unsigned int i = 0; i < system_indices.size(); ++i)
            if (owned_dofs.is_element(system_indices[i]))
              {
                const auto [c, k] = fe->system_to_component_index(i);
                values[system_indices[i]] = component[c][dof_indices[k]];
              }
        }
    values.compress(VectorOperation::insert);
    recovered = values;
  }



  const DoFHandler<2> &
  RecoveredStress::dof_handler() const
  {
    return dofs;
  }



  const TrilinosWrappers::MPI::Vector &
  RecoveredStress::values() const
  {
    return recovered;
  }

} // namespace coulomb_adapt
