#include <deal.II/grid/grid_tools.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <gmsh.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

namespace coulomb_adapt
{
  void
  CoarseMeshData::create_triangulation(Triangulation<2> &tria) const
  {
    tria.clear();
    tria.create_triangulation(vertices, cells, boundary_lines);
  }



  namespace
  {
    // Corner nodes per gmsh element type that we accept (first-order corner
    // nodes come first in gmsh's numbering for every order).
    unsigned int
    n_corners(const int gmsh_element_type)
    {
      switch (gmsh_element_type)
        {
          case 1: // 2-node line
          case 8: // 3-node line
            return 2;
          case 2: // 3-node triangle
          case 9: // 6-node triangle
            return 3;
          case 3:  // 4-node quadrangle
          case 10: // 9-node quadrangle
          case 16: // 8-node quadrangle
            return 4;
          default:
            return 0;
        }
    }



    // Tag of the physical group of dimension dim called name, or -1. Two
    // groups of one name are an error: one of them would be dropped.
    int
    find_physical_group(const int          dim,
                        const std::string &name,
                        const std::string &file_name)
    {
      gmsh::vectorpair groups;
      gmsh::model::getPhysicalGroups(groups, dim);
      int found = -1;
      for (const auto &[d, tag] : groups)
        {
          std::string group_name;
          gmsh::model::getPhysicalName(d, tag, group_name);
          if (group_name != name)
            continue;
          if (found >= 0)
            throw ParameterError(
              "gmsh file '" + file_name + "' has two physical " +
              (dim == 2 ? "surfaces" : "curves") + " named '" + name +
              "' (tags " + std::to_string(found) + " and " +
              std::to_string(tag) + "); give each name to one group");
          found = tag;
        }
      return found;
    }



    // Node tags of all elements of the entities of a physical group,
    // grouped by element (corner nodes only).
    std::vector<std::vector<std::size_t>>
    elements_of_group(const int          dim,
                      const int          group_tag,
                      const std::string &file_name)
    {
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(dim, group_tag, entities);
      std::vector<std::vector<std::size_t>> elements;
      for (const int entity : entities)
        {
          std::vector<int>                      types;
          std::vector<std::vector<std::size_t>> element_tags, node_tags;
          gmsh::model::mesh::getElements(
            types, element_tags, node_tags, dim, entity);
          for (unsigned int t = 0; t < types.size(); ++t)
            {
              std::string type_name;
              int         element_dim, order, n_nodes, n_primary;
              std::vector<double> local_coordinates;
              gmsh::model::mesh::getElementProperties(types[t],
                                                      type_name,
                                                      element_dim,
                                                      order,
                                                      n_nodes,
                                                      local_coordinates,
                                                      n_primary);
              const unsigned int corners = n_corners(types[t]);
              if (corners == 0)
                throw ParameterError("gmsh file '" + file_name +
                                     "': element type '" + type_name +
                                     "' is not supported (allowed: lines, "
                                     "triangles, quadrangles)");
              for (std::size_t e = 0; e < element_tags[t].size(); ++e)
                elements.emplace_back(
                  node_tags[t].begin() + e * n_nodes,
                  node_tags[t].begin() + e * n_nodes + corners);
            }
        }
      return elements;
    }



    double
    signed_area(const std::vector<Point<2>> &polygon)
    {
      double a = 0;
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
          a += p[0] * q[1] - q[0] * p[1];
        }
      return 0.5 * a;
    }
  } // namespace



  // Build one body's mesh from the elements of its physical surface and
  // the boundary lines of the named curve groups.
  CoarseMeshData
  build_body_mesh(const std::vector<std::vector<std::size_t>> &elements,
               const std::map<std::size_t, Point<2>> &      all_nodes,
               const std::map<types::boundary_id,
                              std::vector<std::vector<std::size_t>>> &lines,
               const types::material_id material_id,
               const std::string &      file_name)
    {
      CoarseMeshData                  mesh;
      std::map<std::size_t, unsigned> local_index;
      const unsigned int corners = elements.front().size();
      for (const auto &element : elements)
        {
          if (element.size() != corners)
            throw ParameterError("gmsh file '" + file_name +
                                 "': a body mixes triangles and "
                                 "quadrangles, which is not supported");
          CellData<2> cell(corners);
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
      for (const auto &[id, group_lines] : lines)
        for (const auto &line : group_lines)
          {
            const auto a = local_index.find(line[0]);
            const auto b = local_index.find(line[1]);
            if (a == local_index.end() || b == local_index.end())
              continue;
            const auto edge = std::minmax(a->second, b->second);
            const auto count = edge_count.find(edge);
            if (count == edge_count.end() || count->second != 1)
              continue;
            CellData<1> boundary_line;
            boundary_line.vertices    = {edge.first, edge.second};
            boundary_line.boundary_id = id;
            mesh.boundary_lines.boundary_lines.push_back(boundary_line);
          }

      if (corners == 4)
        GridTools::consistently_order_cells(mesh.cells);
      return mesh;
    }


  namespace
  {
    // Read and check the file with gmsh (on one rank).
    std::array<CoarseMeshData, 2>
    read_with_gmsh(const std::string &file_name,
                   const CellType     requested_cell_type,
                   const double       mesh_size_factor)
    {
      std::array<CoarseMeshData, 2> meshes;
      gmsh::open(file_name);
      if (std::filesystem::path(file_name).extension() == ".geo")
        {
          gmsh::option::setNumber("Mesh.MeshSizeFactor", mesh_size_factor);
          if (requested_cell_type == CellType::quadrilateral)
            {
              gmsh::option::setNumber("Mesh.RecombineAll", 1);
              // Subdivide so that every cell is a quadrangle.
              gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 1);
            }
          gmsh::model::mesh::generate(2);
        }

      std::vector<std::size_t> node_tags;
      std::vector<double>      coordinates, parametric;
      gmsh::model::mesh::getNodes(
        node_tags, coordinates, parametric, -1, -1, false, false);
      std::map<std::size_t, Point<2>> nodes;
      for (std::size_t i = 0; i < node_tags.size(); ++i)
        nodes[node_tags[i]] =
          Point<2>(coordinates[3 * i], coordinates[3 * i + 1]);

      auto require_group = [&](const int dim, const std::string &name) {
        const int tag = find_physical_group(dim, name, file_name);
        if (tag < 0)
          throw ParameterError(
            "gmsh file '" + file_name + "' has no physical " +
            (dim == 2 ? "surface" : "curve") + " named '" + name +
            "'; required: surfaces 'body 1', 'body 2' and curves "
            "'dirichlet', 'traction', 'contact'");
        return tag;
      };

      std::map<types::boundary_id, std::vector<std::vector<std::size_t>>>
        lines;
      lines[boundary_ids::dirichlet] =
        elements_of_group(1, require_group(1, "dirichlet"), file_name);
      lines[boundary_ids::traction] =
        elements_of_group(1, require_group(1, "traction"), file_name);
      lines[boundary_ids::contact] =
        elements_of_group(1, require_group(1, "contact"), file_name);

      // An element may name a node that the file does not define (a
      // hand-edited or truncated file); gmsh does not check it.
      for (const auto &[id, group_lines] : lines)
        for (const auto &line : group_lines)
          for (const std::size_t node : line)
            if (nodes.count(node) == 0)
              throw ParameterError("gmsh file '" + file_name +
                                   "': a line element refers to node " +
                                   std::to_string(node) +
                                   ", which is not in $Nodes");

      for (unsigned int b = 0; b < 2; ++b)
        {
          const std::string name = "body " + std::to_string(b + 1);
          const auto        elements =
            elements_of_group(2, require_group(2, name), file_name);
          if (elements.empty())
            throw ParameterError("gmsh file '" + file_name +
                                 "': physical surface '" + name +
                                 "' has no elements");
          for (const auto &element : elements)
            for (const std::size_t node : element)
              if (nodes.count(node) == 0)
                throw ParameterError("gmsh file '" + file_name +
                                     "': an element of '" + name +
                                     "' refers to node " +
                                     std::to_string(node) +
                                     ", which is not in $Nodes");
          meshes[b] = build_body_mesh(elements, nodes, lines, b, file_name);
        }
      return meshes;
    }
  } // namespace



  std::string
  gmsh_error_message(const std::string &thrown)
  {
    // gmsh's API throws its error message as a std::string (or, for some
    // errors, an int); its logger holds the last error in either case.
    std::string last_error;
    try
      {
        gmsh::logger::getLastError(last_error);
      }
    catch (...)
      {}
    std::string message = last_error.empty() ? thrown : last_error;
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    return message.empty() ? "an error without a message" : message;
  }



  std::array<CoarseMeshData, 2>
  read_two_body_gmsh_file(const std::string &file_name,
                          const CellType     requested_cell_type,
                          const double       mesh_size_factor,
                          const MPI_Comm     comm)
  {
    if (!std::filesystem::is_regular_file(file_name))
      throw ParameterError("Scene/Gmsh/Mesh file",
                           file_name,
                           "no such file (give a .geo or .msh file; "
                           "relative paths are taken from the directory "
                           "the program runs in)");

    // One rank reads (gmsh is serial, and meshing a .geo on every rank
    // would only repeat the work); every rank then either gets the meshes
    // or throws the same error, so none waits for another that gave up.
    std::array<CoarseMeshData, 2> meshes;
    std::string                   error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 0);
        try
          {
            meshes = read_with_gmsh(file_name,
                                    requested_cell_type,
                                    mesh_size_factor);
          }
        catch (const ParameterError &e)
          {
            error = e.what();
          }
        catch (const std::exception &e)
          {
            error = "gmsh file '" + file_name + "': " + user_message(e);
          }
        catch (const std::string &e)
          {
            error = "gmsh file '" + file_name +
                    "': gmsh cannot read it: " + gmsh_error_message(e);
          }
        catch (...)
          {
            error = "gmsh file '" + file_name +
                    "': gmsh cannot read it: " + gmsh_error_message("");
          }
        gmsh::finalize();
      }
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        error = Utilities::MPI::broadcast(comm, error, 0);
        if (error.empty())
          meshes = Utilities::MPI::broadcast(comm, meshes, 0);
      }
    if (!error.empty())
      throw ParameterError(error);
    return meshes;
  }
} // namespace coulomb_adapt
