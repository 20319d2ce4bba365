#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_model.h>

#include <gmsh.h>

namespace coulomb_adapt
{
  namespace gmsh_model
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



    const char *
    dimension_name(const int dim)
    {
      static const char *names[] = {"point", "curve", "surface", "volume"};
      return names[dim];
    }



    // Every physical group of the open model by name. Two groups of one
    // name are an error: one of them would be dropped.
    std::map<std::string, std::pair<int, int>>
    physical_groups_by_name(const std::string &file_name)
    {
      gmsh::vectorpair groups;
      gmsh::model::getPhysicalGroups(groups);
      std::map<std::string, std::pair<int, int>> by_name;
      for (const auto &[dim, tag] : groups)
        {
          std::string name;
          gmsh::model::getPhysicalName(dim, tag, name);
          const auto [it, inserted] =
            by_name.emplace(name, std::pair(dim, tag));
          if (inserted)
            continue;
          const auto [other_dim, other_tag] = it->second;
          if (other_dim == dim)
            throw ParameterError(
              "gmsh file '" + file_name + "' has two physical " +
              dimension_name(dim) + "s named '" + name + "' (tags " +
              std::to_string(other_tag) + " and " + std::to_string(tag) +
              "); give each name to one group");
          throw ParameterError("gmsh file '" + file_name + "' has a physical " +
                               dimension_name(other_dim) + " and a physical " +
                               dimension_name(dim) + " named '" + name +
                               "'; give each name to one group");
        }
      return by_name;
    }



    std::string
    list_of_groups(const std::map<std::string, std::pair<int, int>> &groups)
    {
      std::string list;
      for (const auto &[name, group] : groups)
        list += std::string(list.empty() ? "" : ", ") +
                dimension_name(group.first) + " '" + name + "'";
      return list.empty() ? "none" : list;
    }



    // Corner node tags of the elements of the entities @p entities of
    // dimension @p dim, each entity once.
    std::vector<std::vector<std::size_t>>
    elements_of_entities(const int               dim,
                         const std::vector<int> &entities,
                         const std::string      &file_name)
    {
      std::vector<std::vector<std::size_t>> elements;
      for (const int entity : entities)
        {
          std::vector<int>                      types;
          std::vector<std::vector<std::size_t>> element_tags, node_tags;
          gmsh::model::mesh::getElements(
            types, element_tags, node_tags, dim, entity);
          for (unsigned int t = 0; t < types.size(); ++t)
            {
              std::string         type_name;
              int                 element_dim, order, n_nodes, n_primary;
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
                elements.emplace_back(node_tags[t].begin() + e * n_nodes,
                                      node_tags[t].begin() + e * n_nodes +
                                        corners);
            }
        }
      return elements;
    }
  } // namespace gmsh_model
} // namespace coulomb_adapt
