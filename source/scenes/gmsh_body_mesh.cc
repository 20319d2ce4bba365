#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <map>
#include <optional>
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



    using LocalIndex = std::map<std::size_t, unsigned int>;
    using LocalEdge  = std::pair<unsigned int, unsigned int>;

    // The cells of @p elements in @p mesh, their corners numbered in
    // @p local_index in the order met. gmsh orders corners
    // counter-clockwise (if the surface's normal points along +z);
    // deal.II wants counter-clockwise triangles and lexicographically
    // numbered quadrilaterals.
    void
    add_cells(const std::vector<std::vector<std::size_t>> &elements,
              const std::map<std::size_t, Point<2>>       &all_nodes,
              const types::material_id                     material_id,
              const std::string                           &file_name,
              CoarseMeshData                              &mesh,
              LocalIndex                                  &local_index)
    {
      const unsigned int corners = elements.front().size();
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
          if (signed_area(polygon) < 0)
            std::reverse(cell.vertices.begin() + 1, cell.vertices.end());
          if (corners == 4)
            std::swap(cell.vertices[2], cell.vertices[3]);
          cell.material_id = material_id;
          mesh.cells.push_back(cell);
        }
    }



    // The boundary edges of the body: those of one of its cells only.
    class BoundaryEdges
    {
    public:
      BoundaryEdges(const std::vector<std::vector<std::size_t>> &elements,
                    const LocalIndex                            &local_index)
        : local_index(local_index)
      {
        for (const auto &element : elements)
          for (unsigned int v = 0; v < element.size(); ++v)
            {
              const unsigned int a = local_index.at(element[v]);
              const unsigned int b =
                local_index.at(element[(v + 1) % element.size()]);
              ++edge_count[std::minmax(a, b)];
            }
      }

      // The edge between the nodes @p a and @p b if it is a boundary edge
      // of this body.
      std::optional<LocalEdge>
      find(const std::size_t a, const std::size_t b) const
      {
        const auto i = local_index.find(a);
        const auto j = local_index.find(b);
        if (i == local_index.end() || j == local_index.end())
          return {};
        const LocalEdge edge  = std::minmax(i->second, j->second);
        const auto      count = edge_count.find(edge);
        if (count == edge_count.end() || count->second != 1)
          return {};
        return edge;
      }

    private:
      const LocalIndex                 &local_index;
      std::map<LocalEdge, unsigned int> edge_count;
    };



    CellData<1>
    boundary_line(const LocalEdge         &edge,
                  const types::boundary_id boundary_id,
                  const types::manifold_id manifold_id)
    {
      CellData<1> line;
      line.vertices    = {edge.first, edge.second};
      line.boundary_id = boundary_id;
      line.manifold_id = manifold_id;
      return line;
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
    CoarseMeshData mesh;
    LocalIndex     local_index;
    add_cells(elements, all_nodes, material_id, file_name, mesh, local_index);

    // Only lines that are boundary edges of this body become boundary
    // lines: a curve shared by both bodies (the contact interface) is
    // then given to each of them.
    const BoundaryEdges boundary_edges(elements, local_index);
    std::set<LocalEdge> named_edges;
    auto               &boundary_lines = mesh.boundary_lines.boundary_lines;
    for (const auto &[id, group_lines] : lines)
      for (const auto &line : group_lines)
        if (const auto edge = boundary_edges.find(line[0], line[1]))
          {
            const auto curved =
              curved_edges.find(std::minmax(line[0], line[1]));
            boundary_lines.push_back(
              boundary_line(*edge,
                            id,
                            curved != curved_edges.end() ?
                              curved->second :
                              numbers::flat_manifold_id));
            named_edges.insert(*edge);
          }
    // The boundary edges on circles that no group names: free, but curved.
    for (const auto &[tags, manifold_id] : curved_edges)
      if (const auto edge = boundary_edges.find(tags.first, tags.second))
        if (named_edges.count(*edge) == 0)
          boundary_lines.push_back(boundary_line(*edge, 0, manifold_id));

    if (elements.front().size() == 4)
      GridTools::consistently_order_cells(mesh.cells);
    return mesh;
  }
} // namespace coulomb_adapt
