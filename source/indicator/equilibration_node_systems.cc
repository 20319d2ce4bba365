#include <deal.II/base/work_stream.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <coulomb_adapt/indicator/equilibration_mesh.h>
#include <coulomb_adapt/indicator/equilibration_node_systems.h>

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
      // The cells around a node, as (cell slot, the node's index in the
      // cell), sorted by CellId: every rank that solves the node's system
      // sets it up in the same order.
      using Star = std::vector<std::pair<unsigned int, unsigned int>>;

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

      // A node's system for one component: A b = r, one row per cell of
      // the star (sum_G eta_{E,G} b_G = the cell's residual minus the known
      // moments), one column per face with unknown moments.
      struct NodeSystem
      {
        FullMatrix<double>        A;
        Vector<double>            r;
        std::vector<unsigned int> columns; // index into the node's faces
      };



      // The faces of the star through the node, and the node's place on
      // each.
      std::vector<std::pair<unsigned int, unsigned int>>
      faces_through(const types::global_dof_index node,
                    const Star                   &star,
                    const std::vector<CellData>  &cells,
                    const std::vector<FaceData>  &faces)
      {
        std::vector<std::pair<unsigned int, unsigned int>> node_faces;
        for (const auto &[slot, k] : star)
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
        return node_faces;
      }



      NodeSystem
      node_system(
        const unsigned int                                        c,
        const Star                                               &star,
        const std::vector<std::pair<unsigned int, unsigned int>> &node_faces,
        const std::vector<CellData>                              &cells,
        const std::vector<FaceData>                              &faces)
      {
        NodeSystem system;
        for (unsigned int e = 0; e < node_faces.size(); ++e)
          if (faces[node_faces[e].first].unknown[c])
            system.columns.push_back(e);
        system.A.reinit(star.size(), system.columns.size());
        system.r.reinit(star.size());
        for (unsigned int row = 0; row < star.size(); ++row)
          {
            const auto [slot, k] = star[row];
            system.r(row)        = cells[slot].residual[k][c];
            for (unsigned int e = 0; e < node_faces.size(); ++e)
              {
                const FaceData &face = faces[node_faces[e].first];
                const int       sign = face.plus == static_cast<int>(slot) ? 1 :
                                       face.minus == static_cast<int>(slot) ? -1 :
                                                                              0;
                if (sign == 0)
                  continue;
                const auto col =
                  std::find(system.columns.begin(), system.columns.end(), e);
                if (col != system.columns.end())
                  system.A(row, col - system.columns.begin()) = sign;
                else
                  system.r(row) -= sign * face.moments[node_faces[e].second][c];
              }
          }
        return system;
      }



      // x = b_avg + A^+ (r - A b_avg): the least-squares solution closest
      // to the averaged moments, in sum |G| (F - F_avg)^2 ~ sum (b -
      // b_avg)^2 / |G| (columns scaled by sqrt|G|; A^+ from the SVD, which
      // @p svd keeps for the other component when its columns are the
      // same). The systems of interior nodes are singular by one: the
      // free parameter is the first null vector of the scaled matrix,
      // mapped back to moments (every rank that solves this system finds
      // the same one).
      void
      solve_least_squares(
        const unsigned int                                        c,
        const NodeSystem                                         &system,
        const std::vector<std::pair<unsigned int, unsigned int>> &node_faces,
        const std::vector<FaceData>                              &faces,
        LAPACKFullMatrix<double>                                 &svd,
        std::vector<unsigned int>                                &svd_columns,
        NodeSolution                                             &solution)
      {
        const unsigned int  n_rows = system.A.m(), n_cols = system.A.n();
        Vector<double>      x0(n_cols), rhs(n_rows), y(n_cols);
        std::vector<double> scale(n_cols);
        for (unsigned int j = 0; j < n_cols; ++j)
          {
            const auto &e = node_faces[system.columns[j]];
            x0(j)         = faces[e.first].average[e.second][c];
            scale[j]      = std::sqrt(faces[e.first].length);
          }
        system.A.vmult(rhs, x0);
        rhs.sadd(-1., 1., system.r);
        if (c == 0 || system.columns != svd_columns)
          {
            svd.reinit(n_rows, n_cols);
            for (unsigned int row = 0; row < n_rows; ++row)
              for (unsigned int j = 0; j < n_cols; ++j)
                svd(row, j) = system.A(row, j) * scale[j];
            svd.compute_svd();
            svd_columns = system.columns;
          }
        const auto  &U    = svd.get_svd_u();
        const auto  &Vt   = svd.get_svd_vt();
        unsigned int rank = 0;
        while (rank < std::min(n_rows, n_cols) &&
               svd.singular_value(rank) > 1e-10 * svd.singular_value(0))
          {
            double coefficient = 0;
            for (unsigned int row = 0; row < n_rows; ++row)
              coefficient += U(row, rank) * rhs(row);
            coefficient /= svd.singular_value(rank);
            for (unsigned int j = 0; j < n_cols; ++j)
              y(j) += coefficient * Vt(rank, j) * scale[j];
            ++rank;
          }
        double largest = 0;
        if (rank < n_cols)
          for (unsigned int j = 0; j < n_cols; ++j)
            largest = std::max(largest, std::abs(Vt(rank, j) * scale[j]));
        Vector<double> defect(n_rows);
        system.A.vmult(defect, y);
        defect -= rhs;
        solution.defect = std::max(solution.defect, defect.linfty_norm());
        for (unsigned int j = 0; j < n_cols; ++j)
          {
            const auto &e = node_faces[system.columns[j]];
            solution.entries.push_back(
              {e.first,
               e.second,
               c,
               x0(j) + y(j),
               rank < n_cols,
               rank < n_cols ? Vt(rank, j) * scale[j] / largest : 0.});
          }
      }
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
      std::map<types::global_dof_index, Star> stars;
      for (unsigned int slot = 0; slot < cells.size(); ++slot)
        for (unsigned int k = 0; k < n_nodes; ++k)
          stars[cells[slot].nodes[k]].emplace_back(slot, k);
      for (auto &[node, star] : stars)
        std::sort(star.begin(), star.end(), [&](const auto &a, const auto &b) {
          return cells[a.first].cell->id() < cells[b.first].cell->id();
        });
      std::set<types::global_dof_index> owned_nodes;
      for (const auto &cell : cells)
        if (cell.owned)
          owned_nodes.insert(cell.nodes.begin(), cell.nodes.end());

      const double largest_residual = largest_cell_residual(cells);

      // The node systems are independent: WorkStream solves them on the
      // threads deal.II may use, and writes their moments in the nodes'
      // order. The systems read only known moments, which no system
      // writes.
      const auto solve_node =
        [&](const std::set<types::global_dof_index>::const_iterator &node,
            int & /*no scratch*/,
            NodeSolution &solution) {
          solution.entries.clear();
          solution.defect        = 0;
          const Star &star       = stars.find(*node)->second;
          const auto  node_faces = faces_through(*node, star, cells, faces);
          // Both components have the same matrix where the same moments
          // are unknown (every interior node): one SVD serves both.
          LAPACKFullMatrix<double>  svd;
          std::vector<unsigned int> svd_columns;
          for (unsigned int c = 0; c < 2; ++c)
            {
              const NodeSystem system =
                node_system(c, star, node_faces, cells, faces);
              if (system.columns.empty())
                solution.defect =
                  std::max(solution.defect, system.r.linfty_norm());
              else
                solve_least_squares(
                  c, system, node_faces, faces, svd, svd_columns, solution);
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
