#include <deal.II/grid/grid_tools.h>

#include <coulomb_adapt/adaptation/boundary_curves.h>
#include <coulomb_adapt/scenes/curve_manifold.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace coulomb_adapt
{
  namespace boundary_geometry
  {
    namespace
    {
      struct BoundaryFace
      {
        unsigned int       a, b;
        types::boundary_id boundary_id;
        types::manifold_id manifold_id;
      };

      // The boundary faces of @p tria as closed chains (the outer boundary
      // and one per hole), each face oriented along its chain's walk.
      std::vector<std::vector<BoundaryFace>>
      boundary_loops(const Triangulation<2> &tria, const std::string &body_name)
      {
        std::vector<BoundaryFace> faces;
        for (const auto &cell : tria.active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              faces.push_back({face->vertex_index(0),
                               face->vertex_index(1),
                               face->boundary_id(),
                               face->manifold_id()});
        std::multimap<unsigned int, unsigned int> at_vertex;
        for (unsigned int f = 0; f < faces.size(); ++f)
          {
            at_vertex.emplace(faces[f].a, f);
            at_vertex.emplace(faces[f].b, f);
          }
        std::vector<bool>                      used(faces.size(), false);
        std::vector<std::vector<BoundaryFace>> loops;
        for (unsigned int first = 0; first < faces.size(); ++first)
          {
            if (used[first])
              continue;
            std::vector<BoundaryFace> loop = {faces[first]};
            used[first]                    = true;
            while (loop.back().b != loop.front().a)
              {
                const unsigned int v     = loop.back().b;
                bool               found = false;
                for (auto [it, end] = at_vertex.equal_range(v); it != end; ++it)
                  if (!used[it->second])
                    {
                      BoundaryFace next = faces[it->second];
                      if (next.a != v)
                        std::swap(next.a, next.b);
                      used[it->second] = true;
                      loop.push_back(next);
                      found = true;
                      break;
                    }
                AssertThrow(found,
                            ExcMessage("remeshing " + body_name +
                                       ": its boundary is not made of closed "
                                       "curves"));
              }
            loops.push_back(loop);
          }
        return loops;
      }



      // @p corners: vertices where a curve must end even inside a straight
      // run or an arc (end points of interior lines).
      std::vector<Curve>
      boundary_curves(const Triangulation<2>          &tria,
                      const std::vector<BoundaryFace> &loop,
                      const std::set<unsigned int>    &corners)
      {
        const auto &vertices  = tria.get_vertices();
        auto        direction = [&](const BoundaryFace &f) {
          const Tensor<1, 2> d = vertices[f.b] - vertices[f.a];
          return d / d.norm();
        };
        // A curve ends where the boundary data change, or where a straight
        // run turns.
        auto breaks_between = [&](const BoundaryFace &f,
                                  const BoundaryFace &g) {
          if (f.boundary_id != g.boundary_id ||
              f.manifold_id != g.manifold_id || corners.count(g.a) > 0)
            return true;
          if (f.manifold_id != numbers::flat_manifold_id)
            return false;
          const Tensor<1, 2> s = direction(f), t = direction(g);
          return std::abs(s[0] * t[1] - s[1] * t[0]) > 1e-10 || s * t < 0;
        };
        const unsigned int n     = loop.size();
        unsigned int       start = 0;
        while (start < n &&
               !breaks_between(loop[(start + n - 1) % n], loop[start]))
          ++start;
        if (start == n) // a closed smooth curve: any vertex will do
          start = 0;

        std::vector<Curve> curves;
        for (unsigned int k = 0; k < n; ++k)
          {
            const BoundaryFace &f = loop[(start + k) % n];
            if (k == 0 || breaks_between(loop[(start + k + n - 1) % n], f))
              curves.push_back({{f.a}, f.boundary_id, f.manifold_id});
            curves.back().vertices.push_back(f.b);
          }
        return curves;
      }
    } // namespace



    // An interior line's ends must be vertices of the boundary: the new
    // mesh gets a line of nodes between them, and a curve ends at each.
    InteriorFeatures
    interior_features(
      const Triangulation<2>                     &geometry,
      const std::string                          &body_name,
      const std::vector<std::array<Point<2>, 2>> &interior_lines,
      const std::vector<Point<2>>                &support_points)
    {
      const auto  &vertices  = geometry.get_vertices();
      const double tolerance = 1e-10 * GridTools::diameter(geometry);
      const auto   boundary_vertices =
        GridTools::get_all_vertices_at_boundary(geometry);
      InteriorFeatures features;
      for (const auto &line : interior_lines)
        {
          std::array<unsigned int, 2> ends;
          for (unsigned int e = 0; e < 2; ++e)
            {
              ends[e] =
                GridTools::find_closest_vertex(boundary_vertices, line[e]);
              AssertThrow(vertices[ends[e]].distance(line[e]) < tolerance,
                          ExcMessage("remeshing " + body_name +
                                     ": the end of an interior line (a "
                                     "symmetry line) is not a vertex of the "
                                     "boundary"));
              features.corners.insert(ends[e]);
            }
          features.line_ends.push_back(ends);
        }
      // Point supports: on the boundary a curve ends there, inside the body
      // the point is embedded; either way it stays a node.
      for (const auto &p : support_points)
        {
          const unsigned int v =
            GridTools::find_closest_vertex(boundary_vertices, p);
          if (vertices[v].distance(p) < tolerance)
            features.corners.insert(v);
          else
            features.embedded_points.push_back(p);
        }
      return features;
    }



    unsigned int
    LoopCurves::n_loops() const
    {
      return first_curve_of_loop.size() - 1;
    }



    unsigned int
    LoopCurves::loop_of_curve(const unsigned int c) const
    {
      return std::upper_bound(first_curve_of_loop.begin(),
                              first_curve_of_loop.end(),
                              c) -
             first_curve_of_loop.begin() - 1;
    }



    namespace
    {
      // Whether @p x lies inside the closed polygon @p polygon (crossing
      // number of a ray in +x direction).
      bool
      inside(const std::vector<Point<2>> &polygon, const Point<2> &x)
      {
        bool               result = false;
        const unsigned int n      = polygon.size();
        for (unsigned int i = 0, j = n - 1; i < n; j = i++)
          {
            const Point<2> &a = polygon[i], &b = polygon[j];
            if ((a[1] > x[1]) != (b[1] > x[1]) &&
                x[0] < a[0] + (x[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]))
              result = !result;
          }
        return result;
      }



      // The loops grouped into parts (see LoopCurves). Loops do not cross,
      // so one vertex of a loop tells whether it lies inside another.
      std::vector<std::vector<unsigned int>>
      connected_parts(const std::vector<std::vector<Point<2>>> &polygons)
      {
        const unsigned int             n = polygons.size();
        std::vector<unsigned int>      depth(n, 0);
        std::vector<std::vector<bool>> contains(n, std::vector<bool>(n, false));
        for (unsigned int l = 0; l < n; ++l)
          for (unsigned int m = 0; m < n; ++m)
            if (m != l && inside(polygons[m], polygons[l][0]))
              {
                contains[m][l] = true;
                ++depth[l];
              }
        std::vector<std::vector<unsigned int>> parts;
        std::vector<unsigned int>              part_of_outer(n, 0);
        for (unsigned int l = 0; l < n; ++l)
          if (depth[l] % 2 == 0)
            {
              part_of_outer[l] = parts.size();
              parts.push_back({l});
            }
        for (unsigned int l = 0; l < n; ++l)
          if (depth[l] % 2 == 1)
            for (unsigned int m = 0; m < n; ++m)
              if (contains[m][l] && depth[m] + 1 == depth[l])
                parts[part_of_outer[m]].push_back(l);
        return parts;
      }
    } // namespace



    unsigned int
    LoopCurves::part_containing(const Point<2> &x) const
    {
      for (unsigned int p = 0; p < parts.size(); ++p)
        if (inside(loop_polygons[parts[p][0]], x) &&
            std::none_of(parts[p].begin() + 1,
                         parts[p].end(),
                         [&](const unsigned int hole) {
                           return inside(loop_polygons[hole], x);
                         }))
          return p;
      return numbers::invalid_unsigned_int;
    }



    LoopCurves
    loop_curves(const Triangulation<2>       &geometry,
                const std::string            &body_name,
                const std::set<unsigned int> &corners)
    {
      const auto &vertices = geometry.get_vertices();
      const auto  loops    = boundary_loops(geometry, body_name);
      LoopCurves  result;
      for (const auto &loop : loops)
        {
          result.first_curve_of_loop.push_back(result.curves.size());
          const auto curves = boundary_curves(geometry, loop, corners);
          result.curves.insert(result.curves.end(),
                               curves.begin(),
                               curves.end());
          result.loop_polygons.emplace_back();
          for (const auto &f : loop)
            result.loop_polygons.back().push_back(vertices[f.a]);
        }
      result.first_curve_of_loop.push_back(result.curves.size());
      result.parts = connected_parts(result.loop_polygons);
      return result;
    }



    // gmsh's nodes on the splines of gmsh_remesher.cc's add_curve_splines()
    // lie on gmsh's interpolation of points of the curve: each node inside
    // a run on a CurveManifold (on two of its lines) goes onto the curve
    // itself. The ends of a run, which other curves share, are old
    // vertices, on it.
    void
    put_nodes_on_curves(const Triangulation<2> &geometry, CoarseMeshData &mesh)
    {
      std::map<std::pair<unsigned int, types::manifold_id>, unsigned int>
        lines_at;
      for (const auto &line : mesh.boundary_lines.boundary_lines)
        if (line.manifold_id != numbers::flat_manifold_id &&
            dynamic_cast<const CurveManifold *>(
              &geometry.get_manifold(line.manifold_id)) != nullptr)
          for (const unsigned int v : line.vertices)
            ++lines_at[{v, line.manifold_id}];
      for (const auto &[vertex_and_id, n_lines] : lines_at)
        if (n_lines == 2)
          {
            const auto &[v, id] = vertex_and_id;
            mesh.vertices[v] =
              static_cast<const CurveManifold &>(geometry.get_manifold(id))
                .project(mesh.vertices[v]);
          }
    }
  } // namespace boundary_geometry
} // namespace coulomb_adapt
