#include <coulomb_adapt/indicator/held_reactions.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace coulomb_adapt
{
  namespace equilibration
  {
    namespace
    {
      // Whether some point constraint holds component @p c at @p x.
      bool
      held(const BodyDescription &description,
           const Point<2>        &x,
           const unsigned int     c)
      {
        for (const auto &constraint : description.point_constraints)
          if (constraint.components[c] && constraint.selects(x))
            return true;
        return false;
      }
    } // namespace



    double
    carry_held_reactions(const BodyDescription &description,
                         std::vector<CellData> &cells,
                         std::vector<FaceData> &faces)
    {
      double uncarried = 0;
      if (description.point_constraints.empty())
        return uncarried;

      std::map<types::global_dof_index, Point<2>> position;
      for (const auto &cell : cells)
        for (unsigned int k = 0; k < cell.nodes.size(); ++k)
          position.emplace(cell.nodes[k], cell.points[k]);

      const auto held_node = [&](const types::global_dof_index node,
                                 const unsigned int            c) {
        return held(description, position.at(node), c);
      };

      // The held faces per component: inside the body, every node held,
      // or, for degree >= 2, the nodes inside the face held and one of its
      // ends: the last face of a held line that stops short of a free
      // point (hertz holds its axis but not the contact point; the held
      // midpoint of that face had its reaction carried by no face, 6.8e-6
      // of the largest residual on P2, found by a walkthrough). A face
      // across the line holds at most one end and no inside node.
      std::array<std::vector<unsigned int>, 2> held_faces;
      for (unsigned int f = 0; f < faces.size(); ++f)
        if (faces[f].plus >= 0 && faces[f].minus >= 0 && !faces[f].at_boundary)
          for (unsigned int c = 0; c < 2; ++c)
            {
              const FaceData &face      = faces[f];
              unsigned int    held_ends = 0, free_ends = 0, held_inside = 0,
                           free_inside = 0;
              for (unsigned int k = 0; k < face.nodes.size(); ++k)
                {
                  const bool end = is_face_end(face, k);
                  const bool h   = held_node(face.nodes[k], c);
                  (end ? (h ? held_ends : free_ends) :
                         (h ? held_inside : free_inside)) += 1;
                }
              if (free_inside == 0 &&
                  (free_ends == 0 || (held_inside > 0 && held_ends > 0)))
                held_faces[c].push_back(f);
            }

      // R_k: the residuals of the cells around node k less its known
      // boundary moments. A Dirichlet face at the node (unknown moments
      // on the boundary) takes the reaction already.
      std::map<types::global_dof_index, std::array<double, 2>> reaction;
      std::map<types::global_dof_index, std::array<bool, 2>>   supported;
      for (const auto &cell : cells)
        for (unsigned int k = 0; k < cell.nodes.size(); ++k)
          for (unsigned int c = 0; c < 2; ++c)
            reaction[cell.nodes[k]][c] += cell.residual[k][c];
      for (const auto &face : faces)
        if (face.at_boundary)
          for (unsigned int k = 0; k < face.nodes.size(); ++k)
            for (unsigned int c = 0; c < 2; ++c)
              {
                if (face.unknown[c])
                  supported[face.nodes[k]][c] = true;
                else
                  reaction[face.nodes[k]][c] -= face.moments[k][c];
              }
      const auto is_supported = [&](const types::global_dof_index node,
                                    const unsigned int            c) {
        const auto s = supported.find(node);
        return s != supported.end() && s->second[c];
      };

      // Each node's held faces share its reaction by their lengths.
      // (A free end of a held face carries nothing.)
      std::map<types::global_dof_index, std::array<double, 2>> held_length;
      for (unsigned int c = 0; c < 2; ++c)
        for (const unsigned int f : held_faces[c])
          for (const auto node : faces[f].nodes)
            if (held_node(node, c))
              held_length[node][c] += faces[f].length;

      // What no held face carries: held nodes of owned cells (whose
      // stars, hence reactions, are complete here) off the held lines.
      const double largest_residual = largest_cell_residual(cells);
      for (const auto &cell : cells)
        if (cell.owned)
          for (unsigned int k = 0; k < cell.nodes.size(); ++k)
            for (unsigned int c = 0; c < 2; ++c)
              {
                const auto node = cell.nodes[k];
                const auto l    = held_length.find(node);
                if (held(description, cell.points[k], c) &&
                    !is_supported(node, c) &&
                    !(l != held_length.end() && l->second[c] > 0) &&
                    largest_residual > 0)
                  uncarried =
                    std::max(uncarried,
                             std::abs(reaction.at(node)[c]) / largest_residual);
              }

      for (unsigned int c = 0; c < 2; ++c)
        for (const unsigned int f : held_faces[c])
          {
            FaceData &face = faces[f];
            if (face.held_moments.empty())
              face.held_moments.assign(face.nodes.size(), {{0., 0.}});
            for (unsigned int k = 0; k < face.nodes.size(); ++k)
              {
                const auto node = face.nodes[k];
                if (is_supported(node, c) || !held_node(node, c))
                  continue;
                face.held_moments[k][c] = 0.5 * reaction.at(node)[c] *
                                          face.length / held_length.at(node)[c];
              }
          }

      // Both cells of a held face carry g: their residuals less its
      // moments (the local node k of the cell is found by its DoF).
      for (auto &cell : cells)
        for (const unsigned int f : cell.faces)
          if (!faces[f].held_moments.empty())
            {
              const FaceData &face = faces[f];
              for (unsigned int j = 0; j < face.nodes.size(); ++j)
                for (unsigned int k = 0; k < cell.nodes.size(); ++k)
                  if (cell.nodes[k] == face.nodes[j])
                    for (unsigned int c = 0; c < 2; ++c)
                      cell.residual[k][c] -= face.held_moments[j][c];
            }
      return uncarried;
    }
  } // namespace equilibration
} // namespace coulomb_adapt
