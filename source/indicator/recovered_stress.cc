#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <coulomb_adapt/indicator/recovered_stress.h>

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
  // so one block-diagonal system of the FESystem solves all three at once.
  // The mass matrix is spectrally equivalent to its diagonal on any shape-
  // regular mesh, graded or not: CG with Jacobi converges in a number of
  // steps independent of the mesh size.
  void
  RecoveredStress::project_l2(const TrilinosWrappers::MPI::Vector &displacement)
  {
    const MPI_Comm comm = body.triangulation().get_communicator();

    DynamicSparsityPattern dsp(relevant_dofs);
    Table<2, DoFTools::Coupling> coupling(3, 3);
    for (unsigned int c = 0; c < 3; ++c)
      for (unsigned int d = 0; d < 3; ++d)
        coupling[c][d] = (c == d) ? DoFTools::always : DoFTools::none;
    DoFTools::make_sparsity_pattern(dofs, coupling, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               owned_dofs,
                                               comm,
                                               relevant_dofs);
    TrilinosWrappers::SparseMatrix mass;
    mass.reinit(owned_dofs, owned_dofs, dsp, comm);
    TrilinosWrappers::MPI::Vector rhs(owned_dofs, comm);

    const Quadrature<2> &quadrature = body.cell_quadrature();
    FEValues<2>          stress_values(body.mapping(),
                              *fe,
                              quadrature,
                              update_values | update_JxW_values);
    FEValues<2>          displacement_values(body.mapping(),
                                    body.dof_handler().get_fe(),
                                    quadrature,
                                    update_gradients);
    const FEValuesExtractors::Vector   u(0);
    const unsigned int                 n_dofs = fe->n_dofs_per_cell();
    FullMatrix<double>                 cell_matrix(n_dofs, n_dofs);
    Vector<double>                     cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<SymmetricTensor<2, 2>> strains(quadrature.size());

    for (const auto &cell : dofs.active_cell_iterators())
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
            cell_matrix = 0;
            cell_rhs    = 0;
            for (const unsigned int q : stress_values.quadrature_point_indices())
              {
                const Tensor<1, 3> sigma =
                  stress_components(body.material().stress(strains[q]));
                const double JxW = stress_values.JxW(q);
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    const unsigned int ci = fe->system_to_component_index(i).first;
                    const double       phi_i = stress_values.shape_value(i, q);
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      if (fe->system_to_component_index(j).first == ci)
                        cell_matrix(i, j) +=
                          phi_i * stress_values.shape_value(j, q) * JxW;
                    cell_rhs(i) += phi_i * sigma[ci] * JxW;
                  }
              }
            cell->get_dof_indices(dof_indices);
            constraints.distribute_local_to_global(
              cell_matrix, cell_rhs, dof_indices, mass, rhs);
          }
      }
    mass.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);

    TrilinosWrappers::MPI::Vector   solution(owned_dofs, comm);
    SolverControl                   control(1000, 1e-12 * rhs.l2_norm());
    TrilinosWrappers::SolverCG      cg(control);
    TrilinosWrappers::PreconditionJacobi jacobi;
    jacobi.initialize(mass);
    cg.solve(mass, solution, rhs, jacobi);
    n_cg_iterations = control.last_step();
    constraints.distribute(solution);
    recovered = solution;
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



  unsigned int
  RecoveredStress::projection_iterations() const
  {
    return n_cg_iterations;
  }
} // namespace coulomb_adapt
