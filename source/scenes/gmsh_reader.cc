#include <deal.II/grid/grid_tools.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_model.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>
#include <gmsh.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

namespace coulomb_adapt
{
  namespace
  {
    using namespace gmsh_model;



    using Edge = std::pair<std::size_t, std::size_t>;

    Edge
    edge_of(const std::size_t a, const std::size_t b)
    {
      return std::minmax(a, b);
    }



    // The edges that bound a body: those of one of its elements only.
    std::set<Edge>
    boundary_edges(const std::vector<std::vector<std::size_t>> &elements)
    {
      std::map<Edge, unsigned int> count;
      for (const auto &element : elements)
        for (unsigned int v = 0; v < element.size(); ++v)
          ++count[edge_of(element[v], element[(v + 1) % element.size()])];
      std::set<Edge> edges;
      for (const auto &[edge, n] : count)
        if (n == 1)
          edges.insert(edge);
      return edges;
    }



    // The centre of the circle through @p a, @p b, @p c.
    Point<2>
    circumcentre(const Point<2> &a, const Point<2> &b, const Point<2> &c)
    {
      const Tensor<1, 2> u = b - a, v = c - a;
      const double       d = 2 * (u[0] * v[1] - u[1] * v[0]);
      return a + Tensor<1, 2>(
                   {(v[1] * u.norm_square() - u[1] * v.norm_square()) / d,
                    (u[0] * v.norm_square() - v[0] * u.norm_square()) / d});
    }



    // Read and check the file with gmsh (on one rank).
    TwoBodyGmshMeshes
    read_with_gmsh(const std::string  &file_name,
                   const CellType      requested_cell_type,
                   const double        mesh_size_factor,
                   const GmshGroupUse &use)
    {
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
      const std::string in_file = "gmsh file '" + file_name + "'";

      // The program is two-dimensional: a volume mesh, or nodes off the
      // x-y plane, would otherwise be read as their projection.
      {
        std::vector<int>                      types;
        std::vector<std::vector<std::size_t>> element_tags, node_tags;
        gmsh::model::mesh::getElements(types, element_tags, node_tags, 3);
        if (!types.empty())
          throw ParameterError(in_file +
                               " has volume elements (a 3D mesh); the "
                               "program is two-dimensional: give a 2D mesh "
                               "in the x-y plane");
      }
      std::vector<std::size_t> node_tags;
      std::vector<double>      coordinates, parametric;
      gmsh::model::mesh::getNodes(
        node_tags, coordinates, parametric, -1, -1, false, false);
      std::map<std::size_t, Point<2>> nodes;
      double                          extent = 0;
      for (std::size_t i = 0; i < node_tags.size(); ++i)
        {
          nodes[node_tags[i]] =
            Point<2>(coordinates[3 * i], coordinates[3 * i + 1]);
          extent = std::max({extent,
                             std::abs(coordinates[3 * i]),
                             std::abs(coordinates[3 * i + 1])});
        }
      for (std::size_t i = 0; i < node_tags.size(); ++i)
        if (std::abs(coordinates[3 * i + 2]) > 1e-10 * extent)
          throw ParameterError(in_file + ": node " +
                               std::to_string(node_tags[i]) + " has z = " +
                               Patterns::Tools::Convert<double>::to_string(
                                 coordinates[3 * i + 2]) +
                               "; the program reads 2D meshes in the x-y "
                               "plane (z = 0)");

      // The circle arcs of the geometry (gmsh's curves of type "Circle"; a
      // .msh file's curves are discrete and have none): each circle's
      // centre, from three points of the curve, and its mesh lines. Circles
      // of one centre share a manifold id (deal.II's SphericalManifold does
      // not depend on the radius).
      std::map<Edge, types::manifold_id> curved_edges;
      CircleCentres                      circle_centres;
      {
        gmsh::vectorpair curves;
        gmsh::model::getEntities(curves, 1);
        for (const auto &[dim, tag] : curves)
          {
            std::string type;
            gmsh::model::getType(dim, tag, type);
            if (type != "Circle")
              continue;
            std::vector<double> low, high, xyz;
            gmsh::model::getParametrizationBounds(dim, tag, low, high);
            const double span = high[0] - low[0];
            // Three distinct points also on a closed circle.
            gmsh::model::getValue(dim,
                                  tag,
                                  {low[0],
                                   low[0] + span / 3,
                                   low[0] + 2 * span / 3},
                                  xyz);
            const Point<2>     centre = circumcentre(Point<2>(xyz[0], xyz[1]),
                                                 Point<2>(xyz[3], xyz[4]),
                                                 Point<2>(xyz[6], xyz[7]));
            types::manifold_id id     = circle_centres.size();
            for (const auto &[other_id, other] : circle_centres)
              if (other.distance(centre) <= 1e-10 * extent)
                id = other_id;
            circle_centres.emplace(id, centre);
            for (const auto &line : elements_of_entities(1, {tag}, file_name))
              curved_edges[edge_of(line[0], line[1])] = id;
          }
      }

      const auto groups = physical_groups_by_name(file_name);
      // The entities of group @p name, which @p entry names and which must
      // have dimension @p dim.
      const auto entities_of = [&](const std::string &name,
                                   const int          dim,
                                   const std::string &entry,
                                   const std::string &why) {
        const auto group = groups.find(name);
        if (group == groups.end())
          throw ParameterError(in_file + " has no physical " +
                               dimension_name(dim) + " named '" + name + "' (" +
                               entry +
                               " names it); the file's "
                               "physical groups: " +
                               list_of_groups(groups));
        if (group->second.first != dim)
          throw ParameterError(
            in_file + ": '" + name + "' (" + entry + ") is a physical " +
            dimension_name(group->second.first) + ", not a physical " +
            dimension_name(dim) + ": " + why);
        std::vector<int> tags;
        gmsh::model::getEntitiesForPhysicalGroup(dim,
                                                 group->second.second,
                                                 tags);
        return tags;
      };
      const auto require_known_nodes =
        [&](const std::vector<std::vector<std::size_t>> &elements,
            const std::string                           &what) {
          // An element may name a node that the file does not define (a
          // hand-edited or truncated file); gmsh does not check it.
          for (const auto &element : elements)
            for (const std::size_t node : element)
              if (nodes.count(node) == 0)
                throw ParameterError(in_file + ": " + what +
                                     " refers to node " + std::to_string(node) +
                                     ", which is not in $Nodes");
        };

      // The bodies: their surfaces, none in both.
      std::array<std::vector<std::vector<std::size_t>>, 2> body_elements;
      std::array<std::set<Edge>, 2>                        body_boundary;
      std::map<int, std::pair<unsigned int, std::string>>  body_of_surface;
      for (unsigned int b = 0; b < 2; ++b)
        {
          std::vector<int> surfaces;
          for (const auto &name : use.body_surfaces[b])
            for (const int s : entities_of(
                   name, 2, use.body_entries[b], "a body is made of surfaces"))
              {
                const auto [it, inserted] =
                  body_of_surface.emplace(s, std::pair(b, name));
                if (!inserted && it->second.first != b)
                  throw ParameterError(
                    in_file + ": surface " + std::to_string(s) +
                    " is in both body 1's '" + it->second.second + "' (" +
                    use.body_entries[0] + ") and body 2's '" + name + "' (" +
                    use.body_entries[1] +
                    "); the bodies would overlap: give each surface to one "
                    "body");
                if (std::find(surfaces.begin(), surfaces.end(), s) ==
                    surfaces.end())
                  surfaces.push_back(s);
              }
          body_elements[b]       = elements_of_entities(2, surfaces, file_name);
          const std::string name = "body " + std::to_string(b + 1);
          if (body_elements[b].empty())
            throw ParameterError(in_file + ": " + name + " (" +
                                 use.body_entries[b] + ") has no elements");
          require_known_nodes(body_elements[b], "an element of " + name);
          body_boundary[b] = boundary_edges(body_elements[b]);
        }

      // The lines of the curve groups, with the curve each comes from.
      const auto lines_of = [&](const std::string &name,
                                const std::string &entry,
                                const std::string &why) {
        std::vector<std::pair<Edge, int>> lines;
        for (const int curve : entities_of(name, 1, entry, why))
          for (const auto &line : elements_of_entities(1, {curve}, file_name))
            {
              require_known_nodes({line}, "a line element of '" + name + "'");
              lines.emplace_back(edge_of(line[0], line[1]), curve);
            }
        return lines;
      };
      const auto count_on = [&](const std::vector<std::pair<Edge, int>> &lines,
                                const unsigned int                       b) {
        unsigned int n = 0;
        for (const auto &line : lines)
          n += body_boundary[b].count(line.first);
        return n;
      };

      // The contact pair: the slave group on body 1, the master on body 2.
      const auto &[slave_name, master_name] = use.contact_pair;
      const std::string contact_why         = "contact acts on boundary curves";
      const auto        slave_lines =
        lines_of(slave_name, use.contact_entry, contact_why);
      const auto master_lines =
        slave_name == master_name ?
          slave_lines :
          lines_of(master_name, use.contact_entry, contact_why);
      {
        const unsigned int s1  = count_on(slave_lines, 0),
                           s2  = count_on(slave_lines, 1),
                           m1  = count_on(master_lines, 0),
                           m2  = count_on(master_lines, 1);
        const std::string pair = "the contact pair '" + slave_name + "', '" +
                                 master_name + "' (" + use.contact_entry + ")";
        for (unsigned int b = 0; b < 2; ++b)
          {
            const bool only_this_body =
              b == 0 ? (s2 == 0 && m2 == 0 && s1 > 0 && m1 > 0) :
                       (s1 == 0 && m1 == 0 && s2 > 0 && m2 > 0);
            if (only_this_body)
              throw ParameterError(
                in_file + ": " + pair + " is body " + std::to_string(b + 1) +
                " in contact with itself: both groups lie on body " +
                std::to_string(b + 1) +
                "'s boundary only. The slave group must lie on body 1, the "
                "master group on body 2");
          }
        if (s1 == 0)
          throw ParameterError(
            in_file + ": " + pair + ": the slave group '" + slave_name +
            "' has no line on the boundary of body 1; the slave side is body "
            "1's" +
            (s2 > 0 && m1 > 0 ? std::string(" (swap the pair's groups)") :
                                std::string()));
        if (m2 == 0)
          throw ParameterError(
            in_file + ": " + pair + ": the master group '" + master_name +
            "' has no line on the boundary of body 2; the master side is "
            "body 2's" +
            (m1 > 0 && s2 > 0 ? std::string(" (swap the pair's groups)") :
                                std::string()));
        if (slave_name != master_name && (s2 > 0 || m1 > 0))
          throw ParameterError(
            in_file + ": " + pair + ": the " +
            (s2 > 0 ?
               "slave group '" + slave_name + "' also lies on body 2" :
               "master group '" + master_name + "' also lies on body 1") +
            "; two different contact groups each lie on one body (one group "
            "named as both slave and master may lie on both)");
      }
      std::map<Edge, std::string> contact_group_of;
      for (const auto &[edge, curve] : slave_lines)
        contact_group_of.emplace(edge, slave_name);
      for (const auto &[edge, curve] : master_lines)
        contact_group_of.emplace(edge, master_name);

      // The condition groups: each line gets the set of groups it is in.
      TwoBodyGmshMeshes                         result;
      std::map<Edge, std::vector<unsigned int>> groups_of_line;
      std::vector<Edge>                         condition_lines;
      std::map<Edge, int>                       curve_of_line;
      for (unsigned int g = 0; g < use.condition_groups.size(); ++g)
        {
          const auto &[name, entry] = use.condition_groups[g];
          const auto group          = groups.find(name);
          if (group != groups.end() && group->second.first == 0 &&
              use.point_groups_allowed.count(name) > 0)
            {
              // A point support: the nodes of the group's points, in the
              // body (or bodies) whose node they are.
              std::vector<int> points;
              gmsh::model::getEntitiesForPhysicalGroup(0,
                                                       group->second.second,
                                                       points);
              for (const int point : points)
                {
                  std::vector<std::size_t> tags;
                  std::vector<double>      xyz, uvw;
                  gmsh::model::mesh::getNodes(tags, xyz, uvw, 0, point);
                  for (const std::size_t tag : tags)
                    {
                      bool found = false;
                      for (unsigned int b = 0; b < 2; ++b)
                        for (const auto &element : body_elements[b])
                          if (std::find(element.begin(), element.end(), tag) !=
                              element.end())
                            {
                              result.point_supports.push_back(
                                {name, b, nodes.at(tag)});
                              found = true;
                              break;
                            }
                      if (!found)
                        throw ParameterError(
                          in_file + ": point " + std::to_string(point) +
                          " of '" + name + "' (" + entry +
                          ") is not a node of either body's mesh (embed it "
                          "in a surface: 'Point{...} In Surface{...};')");
                    }
                }
              continue;
            }
          const auto lines =
            lines_of(name,
                     entry,
                     use.point_groups_allowed.count(name) > 0 ?
                       "fixed components act on boundary curves or points" :
                       "boundary conditions and loads act on boundary "
                       "curves");
          if (count_on(lines, 0) + count_on(lines, 1) == 0)
            throw ParameterError(
              in_file + ": '" + name + "' (" + entry +
              ") has no line on the boundary of either body (an interior "
              "curve?); boundary conditions and loads act on boundary "
              "curves");
          for (const auto &[edge, curve] : lines)
            {
              const auto contact = contact_group_of.find(edge);
              if (contact != contact_group_of.end())
                throw ParameterError(
                  in_file + ": curve " + std::to_string(curve) +
                  " is in the contact group '" + contact->second + "' (" +
                  use.contact_entry + ") and in '" + name + "' (" + entry +
                  "); a contact curve takes no other condition or load");
              auto &line_groups = groups_of_line[edge];
              if (line_groups.empty())
                {
                  condition_lines.push_back(edge);
                  curve_of_line[edge] = curve;
                }
              if (line_groups.empty() || line_groups.back() != g)
                line_groups.push_back(g);
            }
        }

      // Boundary ids: contact, clamped, then one per set of groups.
      std::map<std::vector<unsigned int>, types::boundary_id> id_of_set;
      types::boundary_id next_id = boundary_ids::traction;
      std::map<types::boundary_id, std::vector<std::vector<std::size_t>>> lines;
      for (const auto &[edge, curve] : slave_lines)
        lines[boundary_ids::contact].push_back({edge.first, edge.second});
      if (slave_name != master_name)
        for (const auto &[edge, curve] : master_lines)
          lines[boundary_ids::contact].push_back({edge.first, edge.second});
      for (const Edge &edge : condition_lines)
        {
          const auto  &set       = groups_of_line[edge];
          unsigned int n_clamped = 0;
          for (const unsigned int g : set)
            n_clamped +=
              use.clamped_groups.count(use.condition_groups[g].first);
          if (n_clamped > 0 && set.size() > 1)
            {
              const auto is_clamped = [&](const unsigned int g) {
                return use.clamped_groups.count(use.condition_groups[g].first) >
                       0;
              };
              const unsigned int clamped =
                *std::find_if(set.begin(), set.end(), is_clamped);
              const unsigned int other = set[0] == clamped ? set[1] : set[0];
              throw ParameterError(
                in_file + ": curve " + std::to_string(curve_of_line[edge]) +
                " is in '" + use.condition_groups[clamped].first +
                "', clamped in x and y (" +
                use.condition_groups[clamped].second + "), and in '" +
                use.condition_groups[other].first + "' (" +
                use.condition_groups[other].second +
                "); a clamped curve takes no other condition or load");
            }
          types::boundary_id id;
          if (n_clamped > 0)
            id = boundary_ids::dirichlet;
          else
            {
              const auto [it, inserted] = id_of_set.emplace(set, next_id);
              if (inserted)
                {
                  if (next_id == numbers::internal_face_boundary_id - 1)
                    throw ParameterError(in_file + ": too many combinations of "
                                                   "condition groups");
                  ++next_id;
                }
              id = it->second;
            }
          if (result.groups_of_boundary_id.count(id) == 0)
            for (const unsigned int g : set)
              result.groups_of_boundary_id[id].push_back(
                use.condition_groups[g].first);
          lines[id].push_back({edge.first, edge.second});
        }

      for (unsigned int b = 0; b < 2; ++b)
        result.meshes[b] = build_body_mesh(
          body_elements[b], nodes, lines, b, file_name, curved_edges);
      result.circle_centres = circle_centres;
      return result;
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
    while (!message.empty() &&
           (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    return message.empty() ? "an error without a message" : message;
  }



  TwoBodyGmshMeshes
  read_two_body_gmsh_geometry(const std::string  &file_name,
                              const CellType      requested_cell_type,
                              const double        mesh_size_factor,
                              const GmshGroupUse &use,
                              const MPI_Comm      comm)
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
    TwoBodyGmshMeshes result;
    std::string       error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 0);
        try
          {
            result = read_with_gmsh(file_name,
                                    requested_cell_type,
                                    mesh_size_factor,
                                    use);
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
          result = Utilities::MPI::broadcast(comm, result, 0);
      }
    if (!error.empty())
      throw ParameterError(error);
    return result;
  }



  std::array<CoarseMeshData, 2>
  read_two_body_gmsh_file(const std::string &file_name,
                          const CellType     requested_cell_type,
                          const double       mesh_size_factor,
                          const MPI_Comm     comm)
  {
    return read_two_body_gmsh_geometry(file_name,
                                       requested_cell_type,
                                       mesh_size_factor,
                                       GmshGroupUse(),
                                       comm)
      .meshes;
  }
} // namespace coulomb_adapt
