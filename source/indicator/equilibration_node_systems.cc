#include <deal.II/base/work_stream.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <coulomb_adapt/indicator/equilibration_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace coulomb_adapt
{
  namespace equilibration
  {
    namespace
    {
      // What a node system gives: the moments it solved for (and the
      // null vector) at [face][node on the face][component], and its
      // residual.
      struct NodeSolution
      {
        struct Entry
        {
          unsigned int face, node, component;
          double       moment;
          bool         has_kernel;
          double       kernel;
        };
        std::vector<Entry> entries;
        double             defect = 0;
      };
    } // namespace



    // Step 3 of the element equilibration, for every node of a locally
    // owned cell (its star is then all local: the ghost layer holds every
    // cell that shares a vertex with an owned cell).
    void
    solve_node_systems(const std::vector<CellData> &cells,
                       std::vector<FaceData>       &faces,
                       const unsigned int           n_nodes,
                       EquilibratedStressErrors    &result)
    {
      std::map<types::global_dof_index,
               std::vector<std::pair<unsigned int, unsigned int>>>
        star; // node -> (cell slot, local node)
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        for (unsigned int k = 0; k < n_nodes; ++k)
          star[cells[slot].nodes[k]].emplace_back(slot, k);
      std::set<types::global_dof_index> owned_nodes;
      for (const auto &cell : cells)
        if (cell.owned)
          owned_nodes.insert(cell.nodes.begin(), cell.nodes.end());

      double largest_residual = 0;
      for (const auto &cell : cells)
        for (const auto &r : cell.residual)
          largest_residual =
            std::max({largest_residual, std::abs(r[0]), std::abs(r[1])});

      // The node systems are independent: WorkStream solves them on the
      // threads deal.II may use, and writes their moments in the nodes'
      // order.
      const auto solve_node = [&](const std::set<types::global_dof_index>::
                                    const_iterator &node_iterator,
                                  int & /*scratch*/,
                                  NodeSolution &solution) {
        {
          const types::global_dof_index node = *node_iterator;
          solution.entries.clear();
          solution.defect = 0;
          // Each node sorts its own star (no other node touches it).
          auto &cells_of_node = star.find(node)->second;
          std::sort(cells_of_node.begin(),
                    cells_of_node.end(),
                    [&](const auto &a, const auto &b) {
                      return cells[a.first].cell->id() <
                             cells[b.first].cell->id();
                    });
          // The faces of the star through the node, and the node's place
          // on each.
          std::vector<std::pair<unsigned int, unsigned int>> node_faces;
          for (const auto &[slot, k] : cells_of_node)
            for (const unsigned int fi : cells[slot].faces)
              {
                const auto &nodes = faces[fi].nodes;
                const auto  where = std::find(nodes.begin(), nodes.end(), node);
                if (where != nodes.end() &&
                    std::find_if(node_faces.begin(),
                                 node_faces.end(),
                                 [fi = fi](const auto &e) {
                                   return e.first == fi;
                                 }) == node_faces.end())
                  node_faces.emplace_back(fi, where - nodes.begin());
              }

          // Both components have the same matrix where the same moments
          // are unknown (every interior node): one SVD serves both.
          LAPACKFullMatrix<double>  svd;
          std::vector<unsigned int> svd_columns;
          for (unsigned int c = 0; c < 2; ++c)
            {
              std::vector<unsigned int> columns; // index into node_faces
              for (unsigned int e = 0; e < node_faces.size(); ++e)
                if (faces[node_faces[e].first].unknown[c])
                  columns.push_back(e);
              const unsigned int n_rows = cells_of_node.size();
              const unsigned int n_cols = columns.size();
              FullMatrix<double> A(n_rows, n_cols);
              Vector<double>     r(n_rows);
              for (unsigned int row = 0; row < n_rows; ++row)
                {
                  const auto [slot, k] = cells_of_node[row];
                  r(row)               = cells[slot].residual[k][c];
                  for (unsigned int e = 0; e < node_faces.size(); ++e)
                    {
                      const FaceData &face = faces[node_faces[e].first];
                      const int       sign =
                        face.plus == static_cast<int>(slot)  ? 1 :
                              face.minus == static_cast<int>(slot) ? -1 :
                                                                     0;
                      if (sign == 0)
                        continue;
                      const auto col =
                        std::find(columns.begin(), columns.end(), e);
                      if (col != columns.end())
                        A(row, col - columns.begin()) = sign;
                      else
                        r(row) -= sign * face.moments[node_faces[e].second][c];
                    }
                }
              if (n_cols == 0)
                {
                  solution.defect =
                    std::max(solution.defect, r.linfty_norm());
                  continue;
                }
              // x = b_avg + A^+ (r - A b_avg): the least-squares solution
              // closest to the averaged moments (A^+ from the SVD; the
              // systems of interior nodes are singular by one).
              Vector<double> x0(n_cols), rhs(n_rows), y(n_cols);
              for (unsigned int j = 0; j < n_cols; ++j)
                {
                  const auto &e = node_faces[columns[j]];
                  x0(j)         = faces[e.first].average[e.second][c];
                }
              A.vmult(rhs, x0);
              rhs.sadd(-1., 1., r);
              // Closest in sum |G| (F - F_avg)^2 ~ sum (b - b_avg)^2 / |G|:
              // columns scaled by sqrt|G|.
              std::vector<double> scale(n_cols);
              for (unsigned int j = 0; j < n_cols; ++j)
                scale[j] =
                  std::sqrt(faces[node_faces[columns[j]].first].length);
              if (c == 0 || columns != svd_columns)
                {
                  svd.reinit(n_rows, n_cols);
                  for (unsigned int row = 0; row < n_rows; ++row)
                    for (unsigned int j = 0; j < n_cols; ++j)
                      svd(row, j) = A(row, j) * scale[j];
                  svd.compute_svd();
                  svd_columns = columns;
                }
              const auto &U  = svd.get_svd_u();
              const auto &Vt = svd.get_svd_vt();
              for (unsigned int i = 0; i < std::min(n_rows, n_cols); ++i)
                if (svd.singular_value(i) > 1e-10 * svd.singular_value(0))
                  {
                    double coefficient = 0;
                    for (unsigned int row = 0; row < n_rows; ++row)
                      coefficient += U(row, i) * rhs(row);
                    coefficient /= svd.singular_value(i);
                    for (unsigned int j = 0; j < n_cols; ++j)
                      y(j) += coefficient * Vt(i, j) * scale[j];
                  }
              // The free parameter: the first null vector of the scaled
              // matrix (one per interior or Dirichlet node), mapped back
              // to moments. Every rank that solves this node system finds
              // the same one (same star, same order).
              unsigned int rank = 0;
              while (rank < std::min(n_rows, n_cols) &&
                     svd.singular_value(rank) > 1e-10 * svd.singular_value(0))
                ++rank;
              double largest = 0;
              if (rank < n_cols)
                for (unsigned int j = 0; j < n_cols; ++j)
                  largest = std::max(largest, std::abs(Vt(rank, j) * scale[j]));
              Vector<double> defect(n_rows);
              A.vmult(defect, y);
              defect -= rhs;
              solution.defect = std::max(solution.defect, defect.linfty_norm());
              for (unsigned int j = 0; j < n_cols; ++j)
                {
                  const auto &e = node_faces[columns[j]];
                  solution.entries.push_back(
                    {e.first,
                     e.second,
                     c,
                     x0(j) + y(j),
                     rank < n_cols,
                     rank < n_cols ? Vt(rank, j) * scale[j] / largest : 0.});
                }
            }
        }
      };
      const auto write_node = [&](const NodeSolution &solution) {
        result.node_system_defect =
          std::max(result.node_system_defect, solution.defect);
        for (const auto &e : solution.entries)
          {
            faces[e.face].moments[e.node][e.component] = e.moment;
            if (e.has_kernel)
              faces[e.face].kernel[e.node][e.component] = e.kernel;
          }
      };
      int no_scratch = 0;
      WorkStream::run(owned_nodes.cbegin(),
                      owned_nodes.cend(),
                      solve_node,
                      write_node,
                      no_scratch,
                      NodeSolution());
      if (largest_residual > 0)
        result.node_system_defect /= largest_residual;
    }

  } // namespace equilibration
} // namespace coulomb_adapt
