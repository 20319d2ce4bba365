#include <coulomb_adapt/indicator/element_mass_operator.h>

#include <algorithm>
#include <array>

namespace coulomb_adapt
{
  ElementMassOperator::ElementMassOperator(
    const DoFHandler<2>                                      &dofs,
    const AffineConstraints<double>                          &constraints,
    const std::shared_ptr<const Utilities::MPI::Partitioner> &partitioner,
    const FullMatrix<double>                                 &shape_values,
    const QuadratureStress                                   &weights)
    : constraints(constraints)
    , partitioner(partitioner)
    , n_dofs_per_cell(dofs.get_fe().n_dofs_per_cell())
  {
    AssertDimension(partitioner->locally_owned_size(),
                    dofs.locally_owned_dofs().n_elements());
    Assert(&dofs.get_triangulation() == &weights.body().triangulation(),
           ExcMessage("The weights belong to another mesh."));
    Assert(!constraints.has_inhomogeneities(),
           ExcMessage("The mass operator takes homogeneous constraints."));
    AssertThrow(n_dofs_per_cell <= max_dofs_per_cell,
                ExcMessage("The element mass operator supports up to " +
                           std::to_string(max_dofs_per_cell) +
                           " nodes per cell (Q3), not " +
                           std::to_string(n_dofs_per_cell) + "."));
    AssertDimension(shape_values.m(), n_dofs_per_cell);
    AssertDimension(shape_values.n(), weights.n_points());
    // std::size_t: n_cells * n^2 entries in all.
    const std::size_t  n_cells  = weights.n_cells();
    const unsigned int n_points = weights.n_points();
    local_indices.resize(n_cells * n_dofs_per_cell);
    global_indices.resize(n_cells * n_dofs_per_cell);
    cell_is_constrained.assign(n_cells, 0);
    cell_matrices.assign(n_cells * n_dofs_per_cell * n_dofs_per_cell, 0.);

    std::vector<types::global_dof_index> dof_indices(n_dofs_per_cell);
    unsigned int                         owned_cell = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          const unsigned int first = owned_cell * n_dofs_per_cell;
          for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
            {
              global_indices[first + i] = dof_indices[i];
              local_indices[first + i] =
                partitioner->global_to_local(dof_indices[i]);
              if (constraints.is_constrained(dof_indices[i]))
                cell_is_constrained[owned_cell] = 1;
            }
          double *matrix = &cell_matrices[std::size_t(first) * n_dofs_per_cell];
          for (unsigned int q = 0; q < n_points; ++q)
            {
              const double JxW = weights.JxW(owned_cell, q);
              for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
                {
                  const double phi_i = shape_values(i, q) * JxW;
                  for (unsigned int j = 0; j < n_dofs_per_cell; ++j)
                    matrix[i * n_dofs_per_cell + j] +=
                      phi_i * shape_values(j, q);
                }
            }
          ++owned_cell;
        }
    AssertDimension(owned_cell, n_cells);

    for (const auto &line : constraints.get_lines())
      if (partitioner->in_local_range(line.index))
        constrained_local_dofs.push_back(
          partitioner->global_to_local(line.index));

    compute_inverse_diagonal();
  }



  void
  ElementMassOperator::initialize_dof_vector(VectorType &vector) const
  {
    vector.reinit(partitioner);
  }



  void
  ElementMassOperator::initialize_dof_vector(BlockVectorType &vector) const
  {
    vector.reinit(n_blocks);
    for (unsigned int b = 0; b < n_blocks; ++b)
      initialize_dof_vector(vector.block(b));
    vector.collect_sizes();
  }



  // Cells without hanging nodes (all of them on a conforming mesh) read and
  // write the vectors directly; the others go through AffineConstraints,
  // which expands a constrained DoF into its masters.
  void
  ElementMassOperator::vmult(BlockVectorType       &dst,
                             const BlockVectorType &src) const
  {
    AssertDimension(dst.n_blocks(), n_blocks);
    AssertDimension(src.n_blocks(), n_blocks);
    // The ghost entries of src are read; a vector that came without them
    // is left as it came, as CG expects of its operator.
    const bool src_had_ghost_values = src.has_ghost_elements();
    if (!src_had_ghost_values)
      src.update_ghost_values();
    // Also zeroes the ghost entries, which the cell loop adds into.
    dst = 0;
    // The element loops with the number of nodes known to the compiler:
    // for 3 or 4 nodes a loop of unknown length costs more in control than
    // in arithmetic.
    switch (n_dofs_per_cell)
      {
        case 3:
          apply_element_matrices<3>(dst, src);
          break;
        case 4:
          apply_element_matrices<4>(dst, src);
          break;
        case 6:
          apply_element_matrices<6>(dst, src);
          break;
        case 9:
          apply_element_matrices<9>(dst, src);
          break;
        default:
          apply_element_matrices<0>(dst, src);
      }
    dst.compress(VectorOperation::add);
    for (unsigned int b = 0; b < n_blocks; ++b)
      for (const unsigned int i : constrained_local_dofs)
        dst.block(b).local_element(i) = src.block(b).local_element(i);
    if (!src_had_ghost_values)
      src.zero_out_ghost_values();
  }



  template <unsigned int n_static>
  void
  ElementMassOperator::apply_element_matrices(BlockVectorType       &dst,
                                              const BlockVectorType &src) const
  {
    const unsigned int n = n_static > 0 ? n_static : n_dofs_per_cell;
    // Raw arrays of the blocks (owned entries, then ghosts), so that the
    // inner loops see plain pointers.
    std::array<const double *, n_blocks> in;
    std::array<double *, n_blocks>       out;
    for (unsigned int b = 0; b < n_blocks; ++b)
      {
        in[b]  = src.block(b).get_values();
        out[b] = dst.block(b).get_values();
      }
    std::array<std::array<double, max_dofs_per_cell>, n_blocks> x;
    std::array<double, max_dofs_per_cell>                       y;
    for (unsigned int cell = 0; cell < cell_is_constrained.size(); ++cell)
      {
        const unsigned int *indices = &local_indices[cell * n];
        const double       *matrix  = &cell_matrices[std::size_t(cell) * n * n];
        if (cell_is_constrained[cell])
          {
            for (unsigned int b = 0; b < n_blocks; ++b)
              {
                constraints.get_dof_values(src.block(b),
                                           &global_indices[cell * n],
                                           x[b].begin(),
                                           x[b].begin() + n);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    double sum = 0;
                    for (unsigned int j = 0; j < n; ++j)
                      sum += matrix[i * n + j] * x[b][j];
                    y[i] = sum;
                  }
                distribute_local_to_global(cell,
                                           make_array_view(y.begin(),
                                                           y.begin() + n),
                                           dst.block(b));
              }
            continue;
          }
        for (unsigned int b = 0; b < n_blocks; ++b)
          for (unsigned int j = 0; j < n; ++j)
            x[b][j] = in[b][indices[j]];
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int b = 0; b < n_blocks; ++b)
            {
              double sum = 0;
              for (unsigned int j = 0; j < n; ++j)
                sum += matrix[i * n + j] * x[b][j];
              out[b][indices[i]] += sum;
            }
      }
  }



  void
  ElementMassOperator::precondition_Jacobi(BlockVectorType       &dst,
                                           const BlockVectorType &src,
                                           const double           omega) const
  {
    AssertDimension(dst.n_blocks(), n_blocks);
    AssertDimension(src.n_blocks(), n_blocks);
    const unsigned int n_owned = diagonal_inverse.locally_owned_size();
    for (unsigned int b = 0; b < n_blocks; ++b)
      {
        VectorType       &out = dst.block(b);
        const VectorType &in  = src.block(b);
        for (unsigned int i = 0; i < n_owned; ++i)
          out.local_element(i) =
            omega * diagonal_inverse.local_element(i) * in.local_element(i);
      }
  }



  void
  ElementMassOperator::distribute_local_to_global(
    const unsigned int             cell,
    const ArrayView<const double> &cell_vector,
    VectorType                    &dst) const
  {
    AssertDimension(cell_vector.size(), n_dofs_per_cell);
    const unsigned int first = cell * n_dofs_per_cell;
    if (cell_is_constrained[cell])
      constraints.distribute_local_to_global(cell_vector.begin(),
                                             cell_vector.end(),
                                             &global_indices[first],
                                             dst);
    else
      for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
        dst.local_element(local_indices[first + i]) += cell_vector[i];
  }



  // The diagonal of C^T M C. On a cell with hanging nodes, the local DoF a
  // stands for sum_j w_aj x_j over its masters j (w_aj = 1 for a DoF that is
  // not constrained), and master j receives sum_ab w_aj w_bj M_ab.
  void
  ElementMassOperator::compute_inverse_diagonal()
  {
    VectorType &diagonal = diagonal_inverse;
    initialize_dof_vector(diagonal);
    const unsigned int                    n = n_dofs_per_cell;
    std::vector<types::global_dof_index>  masters;
    std::array<double, max_dofs_per_cell> w;
    for (unsigned int cell = 0; cell < cell_is_constrained.size(); ++cell)
      {
        const double *matrix = &cell_matrices[std::size_t(cell) * n * n];
        const types::global_dof_index *dofs = &global_indices[cell * n];
        if (!cell_is_constrained[cell])
          {
            for (unsigned int i = 0; i < n; ++i)
              diagonal.local_element(local_indices[cell * n + i]) +=
                matrix[i * n + i];
            continue;
          }
        masters.clear();
        for (unsigned int a = 0; a < n; ++a)
          if (const auto *entries = constraints.get_constraint_entries(dofs[a]))
            for (const auto &entry : *entries)
              masters.push_back(entry.first);
          else
            masters.push_back(dofs[a]);
        std::sort(masters.begin(), masters.end());
        masters.erase(std::unique(masters.begin(), masters.end()),
                      masters.end());
        for (const types::global_dof_index j : masters)
          {
            for (unsigned int a = 0; a < n; ++a)
              {
                w[a] = 0;
                if (const auto *entries =
                      constraints.get_constraint_entries(dofs[a]))
                  {
                    for (const auto &entry : *entries)
                      if (entry.first == j)
                        w[a] += entry.second;
                  }
                else if (dofs[a] == j)
                  w[a] = 1;
              }
            double value = 0;
            for (unsigned int a = 0; a < n; ++a)
              for (unsigned int b = 0; b < n; ++b)
                value += w[a] * matrix[a * n + b] * w[b];
            diagonal(j) += value;
          }
      }
    diagonal.compress(VectorOperation::add);
    for (const unsigned int i : constrained_local_dofs)
      diagonal.local_element(i) = 1;
    for (unsigned int i = 0; i < diagonal.locally_owned_size(); ++i)
      diagonal.local_element(i) = 1. / diagonal.local_element(i);
  }
} // namespace coulomb_adapt
