#include <deal.II/base/geometry_info.h>

#include <deal.II/grid/cell_id.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <coulomb_adapt/bodies/triangle_mesh_description.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    constexpr unsigned int no_neighbor = numbers::invalid_unsigned_int;

    // An edge by its two vertex indices, in either order.
    std::uint64_t
    edge_key(const unsigned int v, const unsigned int w)
    {
      const auto [a, b] = std::minmax(v, w);
      return (std::uint64_t(a) << 32) | b;
    }

    // deal.II's triangle: face f joins vertices f and f + 1 (mod 3).
    std::uint64_t
    edge_key(const CellData<2> &cell, const unsigned int face)
    {
      return edge_key(cell.vertices[face], cell.vertices[(face + 1) % 3]);
    }



    // Per cell and face, the cell across it (no_neighbor at the boundary),
    // from the sorted edges: an edge met twice is interior.
    std::vector<std::array<unsigned int, 3>>
    face_neighbors(const std::vector<CellData<2>> &cells)
    {
      struct Edge
      {
        std::uint64_t key;
        unsigned int  cell, face;
      };
      std::vector<Edge> edges;
      edges.reserve(3 * cells.size());
      for (unsigned int c = 0; c < cells.size(); ++c)
        for (unsigned int f = 0; f < 3; ++f)
          edges.push_back({edge_key(cells[c], f), c, f});
      std::sort(edges.begin(), edges.end(), [](const Edge &a, const Edge &b) {
        return a.key < b.key;
      });
      std::vector<std::array<unsigned int, 3>> neighbors(
        cells.size(), {{no_neighbor, no_neighbor, no_neighbor}});
      for (std::size_t e = 0; e + 1 < edges.size(); ++e)
        if (edges[e].key == edges[e + 1].key)
          {
            neighbors[edges[e].cell][edges[e].face]         = edges[e + 1].cell;
            neighbors[edges[e + 1].cell][edges[e + 1].face] = edges[e].cell;
          }
      return neighbors;
    }



    // GridTools::partition_triangulation()'s partition: METIS on the graph
    // of cells and their face neighbours (the same graph, so the same
    // partition); one rank owns everything.
    std::vector<unsigned int>
    partition_cells(const std::vector<std::array<unsigned int, 3>> &neighbors,
                    const unsigned int                              n_ranks)
    {
      std::vector<unsigned int> owner(neighbors.size(), 0);
      if (n_ranks == 1)
        return owner;
      DynamicSparsityPattern graph(neighbors.size(), neighbors.size());
      for (unsigned int c = 0; c < neighbors.size(); ++c)
        {
          graph.add(c, c);
          for (const unsigned int n : neighbors[c])
            if (n != no_neighbor)
              {
                graph.add(c, n);
                graph.add(n, c);
              }
        }
      SparsityPattern pattern;
      pattern.copy_from(graph);
      SparsityTools::partition(pattern,
                               std::vector<unsigned int>(),
                               n_ranks,
                               owner,
                               SparsityTools::Partitioner::metis);
      return owner;
    }



    // The listed lines (boundary and manifold ids) by their edge key.
    struct ListedLine
    {
      std::uint64_t      key;
      types::boundary_id boundary_id;
      types::manifold_id manifold_id;
    };

    std::vector<ListedLine>
    sorted_listed_lines(const CoarseMeshData &mesh)
    {
      std::vector<ListedLine> listed;
      for (const auto &line : mesh.boundary_lines.boundary_lines)
        listed.push_back({edge_key(line.vertices[0], line.vertices[1]),
                          line.boundary_id,
                          line.manifold_id});
      std::sort(listed.begin(),
                listed.end(),
                [](const ListedLine &x, const ListedLine &y) {
                  return x.key < y.key;
                });
      return listed;
    }

    // The boundary id and manifold id that the listed lines give face @p f
    // of @p cell (a boundary face not listed: id 0; a line not listed:
    // flat).
    std::pair<types::boundary_id, types::manifold_id>
    face_ids(const std::vector<ListedLine> &listed,
             const CellData<2>             &cell,
             const unsigned int             f,
             const bool                     at_boundary)
    {
      std::pair<types::boundary_id, types::manifold_id> ids(
        at_boundary ? 0 : numbers::internal_face_boundary_id,
        numbers::flat_manifold_id);
      const std::uint64_t key = edge_key(cell, f);
      const auto          line =
        std::lower_bound(listed.begin(),
                         listed.end(),
                         key,
                         [](const ListedLine &l, const std::uint64_t k) {
                           return l.key < k;
                         });
      if (line != listed.end() && line->key == key)
        {
          if (at_boundary)
            ids.first = line->boundary_id;
          ids.second = line->manifold_id;
        }
      return ids;
    }
  } // namespace



  TriangulationDescription::Description<2, 2>
  describe_triangle_mesh(const CoarseMeshData &mesh, const MPI_Comm comm)
  {
    for (const auto &cell : mesh.cells)
      AssertThrow(cell.vertices.size() == 3,
                  ExcMessage("describe_triangle_mesh() takes triangles"));
    const unsigned int my_rank   = Utilities::MPI::this_mpi_process(comm);
    const auto         neighbors = face_neighbors(mesh.cells);
    const auto         owner =
      partition_cells(neighbors, Utilities::MPI::n_mpi_processes(comm));

    // The cells this rank keeps: its own and every cell that shares a
    // vertex with one of them (the ghost layer).
    std::vector<bool> owned_vertex(mesh.vertices.size(), false);
    for (unsigned int c = 0; c < mesh.cells.size(); ++c)
      if (owner[c] == my_rank)
        for (const unsigned int v : mesh.cells[c].vertices)
          owned_vertex[v] = true;
    std::vector<unsigned int> kept;
    std::vector<bool>         kept_vertex(mesh.vertices.size(), false);
    for (unsigned int c = 0; c < mesh.cells.size(); ++c)
      {
        const auto &v = mesh.cells[c].vertices;
        if (owned_vertex[v[0]] || owned_vertex[v[1]] || owned_vertex[v[2]])
          {
            kept.push_back(c);
            for (const unsigned int w : v)
              kept_vertex[w] = true;
          }
      }

    TriangulationDescription::Description<2, 2> description;
    description.comm      = comm;
    description.smoothing = Triangulation<2>::none;
    description.settings  = TriangulationDescription::Settings::default_setting;

    std::vector<unsigned int> local_vertex(mesh.vertices.size(),
                                           numbers::invalid_unsigned_int);
    for (unsigned int v = 0; v < mesh.vertices.size(); ++v)
      if (kept_vertex[v])
        {
          local_vertex[v] = description.coarse_cell_vertices.size();
          description.coarse_cell_vertices.push_back(mesh.vertices[v]);
        }

    // Only the kept cells' faces are looked up.
    const auto listed = sorted_listed_lines(mesh);
    description.cell_infos.resize(1);
    for (const unsigned int c : kept)
      {
        CellData<2> cell(3);
        cell.material_id = mesh.cells[c].material_id;
        cell.manifold_id = mesh.cells[c].manifold_id;
        for (unsigned int v = 0; v < 3; ++v)
          cell.vertices[v] = local_vertex[mesh.cells[c].vertices[v]];
        description.coarse_cells.push_back(cell);
        description.coarse_cell_index_to_coarse_cell_id.push_back(c);

        TriangulationDescription::CellData<2> info;
        info.id                 = CellId(c, {}).template to_binary<2>();
        info.subdomain_id       = owner[c];
        info.level_subdomain_id = 0; // a serial mesh's default
        info.manifold_id        = mesh.cells[c].manifold_id;
        info.manifold_line_ids.fill(numbers::flat_manifold_id);
        for (unsigned int f = 0; f < 3; ++f)
          {
            const auto [boundary_id, manifold_id] = face_ids(
              listed, mesh.cells[c], f, neighbors[c][f] == no_neighbor);
            info.manifold_line_ids[f] = manifold_id;
            if (boundary_id != numbers::internal_face_boundary_id)
              info.boundary_ids.emplace_back(f, boundary_id);
          }
        description.cell_infos[0].push_back(info);
      }
    return description;
  }
} // namespace coulomb_adapt
