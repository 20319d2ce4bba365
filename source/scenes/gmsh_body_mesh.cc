#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <map>
#include <set>
#include <vector>

// One body's coarse mesh (CoarseMeshData) from the corner nodes of the
// elements gmsh read: cells oriented counter-clockwise, and the boundary
// lines of the named curve groups.

namespace coulomb_adapt
{
  void
  CoarseMeshData::create_triangulation(Triangulation<2> &tria) const
  {
    tria.clear();
    tria.create_triangulation(vertices, cells, boundary_lines);
  }



  void
  attach_circle_manifolds(const CircleCentres &centres, Triangulation<2> &tria)
  {
    for (const auto &[id, centre] : centres)
      tria.set_manifold(id, SphericalManifold<2>(centre));
  }



  namespace
  {
    double
    signed_area(const std::vector<Point<2>> &polygon)
    {
      double a = 0;
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &p = polygon[i],
                         &q = polygon[(i + 1) % polygon.size()];
          a += p[0] * q[1] - q[0] * p[1];
        }
      return 0.5 * a;
    }
  } // namespace



  // Build one body's mesh from the elements of its physical surface and
  // the boundary lines of the named curve groups.
  CoarseMeshData
  build_body_mesh(const std::vector<std::vector<std::size_t>> &elements,
                  const std::map<std::size_t, Point<2>>       &all_nodes,
                  const std::map<types::boundary_id,
                                 std::vector<std::vector<std::size_t>>> &lines,
                  const types::material_id            material_id,
                  const std::string                  &file_name,
                  const std::map<std::pair<std::size_t, std::size_t>,
                                 types::manifold_id> &curved_edges)
  {
    CoarseMeshData                  mesh;
    std::map<std::size_t, unsigned> local_index;
    const unsigned int              corners = elements.front().size();
    for (const auto &element : elements)
      {
        if (element.size() != corners)
          throw ParameterError("gmsh file '" + file_name +
                               "': a body mixes triangles and "
                               "quadrangles, which is not supported");
        CellData<2>           cell(corners);
        std::vector<Point<2>> polygon;
        for (unsigned int v = 0; v < corners; ++v)
          {
            const auto [it, inserted] =
              local_index.emplace(element[v], mesh.vertices.size());
            if (inserted)
              mesh.vertices.push_back(all_nodes.at(element[v]));
            cell.vertices[v] = it->second;
            polygon.push_back(mesh.vertices[it->second]);
          }
        // gmsh orders corners counter-clockwise (if the surface's normal
        // points along +z); deal.II wants counter-clockwise triangles
        // and lexicographically numbered quadrilaterals.
        if (signed_area(polygon) < 0)
          std::reverse(cell.vertices.begin() + 1, cell.vertices.end());
        if (corners == 4)
          std::swap(cell.vertices[2], cell.vertices[3]);
        cell.material_id = material_id;
        mesh.cells.push_back(cell);
      }

    // Only lines that are boundary edges of this body become boundary
    // lines: a curve shared by both bodies (the contact interface) is
    // then given to each of them.
    std::map<std::pair<unsigned, unsigned>, unsigned> edge_count;
    for (const auto &element : elements)
      for (unsigned int v = 0; v < corners; ++v)
        {
          unsigned a = local_index[element[v]];
          unsigned b = local_index[element[(v + 1) % corners]];
          ++edge_count[std::minmax(a, b)];
        }
    std::set<std::pair<unsigned, unsigned>> named_edges;
    for (const auto &[id, group_lines] : lines)
      for (const auto &line : group_lines)
        {
          const auto a = local_index.find(line[0]);
          const auto b = local_index.find(line[1]);
          if (a == local_index.end() || b == local_index.end())
            continue;
          const auto edge  = std::minmax(a->second, b->second);
          const auto count = edge_count.find(edge);
          if (count == edge_count.end() || count->second != 1)
            continue;
          CellData<1> boundary_line;
          boundary_line.vertices    = {edge.first, edge.second};
          boundary_line.boundary_id = id;
          const auto curved = curved_edges.find(std::minmax(line[0], line[1]));
          if (curved != curved_edges.end())
            boundary_line.manifold_id = curved->second;
          mesh.boundary_lines.boundary_lines.push_back(boundary_line);
          named_edges.insert(edge);
        }
    // The boundary edges on circles that no group names: free, but curved.
    for (const auto &[tags, manifold_id] : curved_edges)
      {
        const auto a = local_index.find(tags.first);
        const auto b = local_index.find(tags.second);
        if (a == local_index.end() || b == local_index.end())
          continue;
        const auto edge  = std::minmax(a->second, b->second);
        const auto count = edge_count.find(edge);
        if (count == edge_count.end() || count->second != 1 ||
            named_edges.count(edge) > 0)
          continue;
        CellData<1> boundary_line;
        boundary_line.vertices    = {edge.first, edge.second};
        boundary_line.boundary_id = 0;
        boundary_line.manifold_id = manifold_id;
        mesh.boundary_lines.boundary_lines.push_back(boundary_line);
      }

    if (corners == 4)
      GridTools::consistently_order_cells(mesh.cells);
    return mesh;
  }
} // namespace coulomb_adapt
