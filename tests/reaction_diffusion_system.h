// The SPD test system of the solver tests (symmetric_direct_solver,
// truncated_minimisation): -Laplace u + u on the unit square, P2 on
// 16 x 16 squares of a distributed mesh (split between the ranks of a
// 2-rank run), with an irregular load (not aligned with any eigenvector)
// so that every unknown takes part; and the patches an additive Schwarz
// method over its vertices would use.

#ifndef coulomb_adapt_tests_reaction_diffusion_system_h
#define coulomb_adapt_tests_reaction_diffusion_system_h

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace coulomb_adapt
{
  namespace testing
  {

    struct ReactionDiffusionSystem
    {
      TrilinosWrappers::SparseMatrix A;
      TrilinosWrappers::MPI::Vector  b;
      IndexSet                       relevant;
      // Per owned vertex, the unknowns of the cells around it (sorted).
      std::vector<std::vector<types::global_dof_index>> stars;
    };

    // On the unit square refined @p n_refinements times.
    inline ReactionDiffusionSystem
    reaction_diffusion_system(const MPI_Comm     comm,
                              const unsigned int n_refinements = 4)
    {
      parallel::distributed::Triangulation<2> triangulation(comm);
      GridGenerator::hyper_cube(triangulation);
      triangulation.refine_global(n_refinements);
      const FE_Q<2> fe(2);
      DoFHandler<2> dof_handler(triangulation);
      dof_handler.distribute_dofs(fe);
      const IndexSet          owned = dof_handler.locally_owned_dofs();
      ReactionDiffusionSystem system;
      DoFTools::extract_locally_relevant_dofs(dof_handler, system.relevant);
      DynamicSparsityPattern dsp(system.relevant);
      DoFTools::make_sparsity_pattern(dof_handler, dsp);
      SparsityTools::distribute_sparsity_pattern(dsp,
                                                 owned,
                                                 comm,
                                                 system.relevant);
      system.A.reinit(owned, owned, dsp, comm);
      system.b.reinit(owned, comm);
      const QGauss<2>                      quadrature(3);
      FEValues<2>                          fe_values(fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   cell_matrix(n, n);
      Vector<double>                       cell_rhs(n);
      std::vector<types::global_dof_index> indices(n);
      std::map<types::global_dof_index, std::vector<types::global_dof_index>>
        stars;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          {
            cell->get_dof_indices(indices);
            for (const unsigned int v : cell->vertex_indices())
              if (owned.is_element(cell->vertex_dof_index(v, 0)))
                stars[cell->vertex_dof_index(v, 0)].insert(
                  stars[cell->vertex_dof_index(v, 0)].end(),
                  indices.begin(),
                  indices.end());
            if (!cell->is_locally_owned())
              continue;
            fe_values.reinit(cell);
            cell_matrix = 0;
            cell_rhs    = 0;
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                const Point<2> &x    = fe_values.quadrature_point(q);
                const double    load = std::sin(7 * x[0]) + x[1] * x[1] * x[0];
                for (unsigned int i = 0; i < n; ++i)
                  {
                    for (unsigned int j = 0; j < n; ++j)
                      cell_matrix(i, j) += (fe_values.shape_grad(i, q) *
                                              fe_values.shape_grad(j, q) +
                                            fe_values.shape_value(i, q) *
                                              fe_values.shape_value(j, q)) *
                                           fe_values.JxW(q);
                    cell_rhs(i) +=
                      load * fe_values.shape_value(i, q) * fe_values.JxW(q);
                  }
              }
            system.A.add(indices, cell_matrix);
            system.b.add(indices, cell_rhs);
          }
      system.A.compress(VectorOperation::add);
      system.b.compress(VectorOperation::add);
      for (auto &[vertex, star] : stars)
        {
          std::sort(star.begin(), star.end());
          star.erase(std::unique(star.begin(), star.end()), star.end());
          system.stars.push_back(star);
        }
      return system;
    }



    inline double
    relative_difference(const TrilinosWrappers::MPI::Vector &x,
                        const TrilinosWrappers::MPI::Vector &y)
    {
      TrilinosWrappers::MPI::Vector difference(x);
      difference -= y;
      return difference.l2_norm() / y.l2_norm();
    }
  } // namespace testing
} // namespace coulomb_adapt

#endif
