#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_bodies.h>
#include <coulomb_adapt/scenes/gmsh_two_body_reader.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <gmsh.h>

#include <algorithm>
#include <map>

namespace coulomb_adapt
{
  namespace
  {
    using namespace gmsh_model;



    // Reads and checks the two-body file: the bodies (GmshBodies), then
    // the contact pair and the condition groups on their boundaries, each
    // step checked against what the parameter file asks for before the
    // next one uses it, so that an error names the first thing wrong.
    class TwoBodyReader
    {
    public:
      TwoBodyReader(const std::string  &file_name,
                    const GmshGroupUse &use,
                    const CellType      requested_cell_type,
                    const double        mesh_size_factor)
        : use(use)
        , bodies(file_name, use, requested_cell_type, mesh_size_factor)
      {}

      TwoBodyGmshMeshes
      read();

    private:
      using Lines = GmshBodies::Lines;

      void
      read_contact_pair();
      void
      check_contact_pair() const;
      void
      read_condition_groups();
      void
      add_point_supports(const std::string &name,
                         const std::string &entry,
                         const int          group_tag);
      void
      add_condition_lines(const unsigned int g);
      void
      assign_boundary_ids();
      bool
      clamps(const unsigned int g) const;
      void
      check_clamped_alone(const Edge                      &edge,
                          const std::vector<unsigned int> &set) const;

      const GmshGroupUse &use;
      const GmshBodies    bodies;

      Lines                       slave_lines;
      Lines                       master_lines;
      std::map<Edge, std::string> contact_group_of;
      // The condition groups each line is in, the lines in the order met.
      std::map<Edge, std::vector<unsigned int>> groups_of_line;
      std::vector<Edge>                         condition_lines;
      std::map<Edge, int>                       curve_of_line;
      // The lines of each boundary id, for build_body_mesh.
      std::map<types::boundary_id, std::vector<std::vector<std::size_t>>>
                        lines_of_id;
      TwoBodyGmshMeshes result;
    };



    TwoBodyGmshMeshes
    TwoBodyReader::read()
    {
      read_contact_pair();
      read_condition_groups();
      assign_boundary_ids();
      for (unsigned int b = 0; b < 2; ++b)
        result.meshes[b] = build_body_mesh(bodies.body_elements[b],
                                           bodies.nodes,
                                           lines_of_id,
                                           b,
                                           bodies.file_name,
                                           bodies.curved_edges);
      result.circle_centres = bodies.circle_centres;
      result.sampled_curves = bodies.sampled_curves;
      return result;
    }



    // The contact pair: the slave group on body 1, the master on body 2.
    void
    TwoBodyReader::read_contact_pair()
    {
      const auto &[slave_name, master_name] = use.contact_pair;
      const std::string contact_why         = "contact acts on boundary curves";
      slave_lines = bodies.lines_of(slave_name, use.contact_entry, contact_why);
      master_lines =
        slave_name == master_name ?
          slave_lines :
          bodies.lines_of(master_name, use.contact_entry, contact_why);
      check_contact_pair();
      for (const auto &[edge, curve] : slave_lines)
        contact_group_of.emplace(edge, slave_name);
      for (const auto &[edge, curve] : master_lines)
        contact_group_of.emplace(edge, master_name);
    }



    // The slave group must lie on body 1, the master group on body 2; a
    // message says which way a pair is wrong (swapped, on one body only,
    // or one group on both bodies).
    void
    TwoBodyReader::check_contact_pair() const
    {
      const auto &[slave_name, master_name] = use.contact_pair;
      const unsigned int s1                 = bodies.count_on(slave_lines, 0),
                         s2                 = bodies.count_on(slave_lines, 1),
                         m1                 = bodies.count_on(master_lines, 0),
                         m2                 = bodies.count_on(master_lines, 1);
      const std::string pair = "the contact pair '" + slave_name + "', '" +
                               master_name + "' (" + use.contact_entry + ")";
      for (unsigned int b = 0; b < 2; ++b)
        {
          const bool only_this_body =
            b == 0 ? (s2 == 0 && m2 == 0 && s1 > 0 && m1 > 0) :
                     (s1 == 0 && m1 == 0 && s2 > 0 && m2 > 0);
          if (only_this_body)
            throw ParameterError(
              bodies.in_file + ": " + pair + " is body " +
              std::to_string(b + 1) +
              " in contact with itself: both groups lie on body " +
              std::to_string(b + 1) +
              "'s boundary only. The slave group must lie on body 1, the "
              "master group on body 2");
        }
      if (s1 == 0)
        throw ParameterError(
          bodies.in_file + ": " + pair + ": the slave group '" + slave_name +
          "' has no line on the boundary of body 1; the slave side is body "
          "1's" +
          (s2 > 0 && m1 > 0 ? std::string(" (swap the pair's groups)") :
                              std::string()));
      if (m2 == 0)
        throw ParameterError(
          bodies.in_file + ": " + pair + ": the master group '" + master_name +
          "' has no line on the boundary of body 2; the master side is "
          "body 2's" +
          (m1 > 0 && s2 > 0 ? std::string(" (swap the pair's groups)") :
                              std::string()));
      if (slave_name != master_name && (s2 > 0 || m1 > 0))
        throw ParameterError(
          bodies.in_file + ": " + pair + ": the " +
          (s2 > 0 ? "slave group '" + slave_name + "' also lies on body 2" :
                    "master group '" + master_name + "' also lies on body 1") +
          "; two different contact groups each lie on one body (one group "
          "named as both slave and master may lie on both)");
    }



    // The condition groups: each line gets the set of groups it is in; a
    // point group (where allowed) gives point supports instead.
    void
    TwoBodyReader::read_condition_groups()
    {
      for (unsigned int g = 0; g < use.condition_groups.size(); ++g)
        {
          const auto &[name, entry] = use.condition_groups[g];
          const auto group          = bodies.groups.find(name);
          if (group != bodies.groups.end() && group->second.first == 0 &&
              use.point_groups_allowed.count(name) > 0)
            add_point_supports(name, entry, group->second.second);
          else
            add_condition_lines(g);
        }
    }



    // A point support: the nodes of the group's points, in the body (or
    // bodies) whose node they are.
    void
    TwoBodyReader::add_point_supports(const std::string &name,
                                      const std::string &entry,
                                      const int          group_tag)
    {
      std::vector<int> points;
      gmsh::model::getEntitiesForPhysicalGroup(0, group_tag, points);
      for (const int point : points)
        {
          std::vector<std::size_t> tags;
          std::vector<double>      xyz, uvw;
          gmsh::model::mesh::getNodes(tags, xyz, uvw, 0, point);
          for (const std::size_t tag : tags)
            {
              bool found = false;
              for (unsigned int b = 0; b < 2; ++b)
                for (const auto &element : bodies.body_elements[b])
                  if (std::find(element.begin(), element.end(), tag) !=
                      element.end())
                    {
                      result.point_supports.push_back(
                        {name, b, bodies.nodes.at(tag)});
                      found = true;
                      break;
                    }
              if (!found)
                throw ParameterError(
                  bodies.in_file + ": point " + std::to_string(point) +
                  " of '" + name + "' (" + entry +
                  ") is not a node of either body's mesh (embed it "
                  "in a surface: 'Point{...} In Surface{...};')");
            }
        }
    }



    // The lines of condition group @p g, which must lie on a body's
    // boundary and off the contact curves.
    void
    TwoBodyReader::add_condition_lines(const unsigned int g)
    {
      const auto &[name, entry] = use.condition_groups[g];
      const auto lines_of_group =
        bodies.lines_of(name,
                        entry,
                        use.point_groups_allowed.count(name) > 0 ?
                          "fixed components act on boundary curves or points" :
                          "boundary conditions and loads act on boundary "
                          "curves");
      if (bodies.count_on(lines_of_group, 0) +
            bodies.count_on(lines_of_group, 1) ==
          0)
        throw ParameterError(
          bodies.in_file + ": '" + name + "' (" + entry +
          ") has no line on the boundary of either body (an interior "
          "curve?); boundary conditions and loads act on boundary "
          "curves");
      for (const auto &[edge, curve] : lines_of_group)
        {
          const auto contact = contact_group_of.find(edge);
          if (contact != contact_group_of.end())
            throw ParameterError(
              bodies.in_file + ": curve " + std::to_string(curve) +
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
    void
    TwoBodyReader::assign_boundary_ids()
    {
      const auto &[slave_name, master_name] = use.contact_pair;
      for (const auto &[edge, curve] : slave_lines)
        lines_of_id[boundary_ids::contact].push_back({edge.first, edge.second});
      if (slave_name != master_name)
        for (const auto &[edge, curve] : master_lines)
          lines_of_id[boundary_ids::contact].push_back(
            {edge.first, edge.second});
      std::map<std::vector<unsigned int>, types::boundary_id> id_of_set;
      types::boundary_id next_id    = boundary_ids::traction;
      const auto         is_clamped = [this](const unsigned int g) {
        return clamps(g);
      };
      for (const Edge &edge : condition_lines)
        {
          const auto &set = groups_of_line[edge];
          check_clamped_alone(edge, set);
          types::boundary_id id;
          if (std::any_of(set.begin(), set.end(), is_clamped))
            id = boundary_ids::dirichlet;
          else
            {
              const auto [it, inserted] = id_of_set.emplace(set, next_id);
              if (inserted)
                {
                  if (next_id == numbers::internal_face_boundary_id - 1)
                    throw ParameterError(bodies.in_file +
                                         ": too many combinations of "
                                         "condition groups");
                  ++next_id;
                }
              id = it->second;
            }
          if (result.groups_of_boundary_id.count(id) == 0)
            for (const unsigned int g : set)
              result.groups_of_boundary_id[id].push_back(
                use.condition_groups[g].first);
          lines_of_id[id].push_back({edge.first, edge.second});
        }
    }



    // Whether condition group @p g clamps both components.
    bool
    TwoBodyReader::clamps(const unsigned int g) const
    {
      return use.clamped_groups.count(use.condition_groups[g].first) > 0;
    }



    // A clamped curve takes no other condition or load: the clamp would
    // silently override it.
    void
    TwoBodyReader::check_clamped_alone(
      const Edge                      &edge,
      const std::vector<unsigned int> &set) const
    {
      const auto is_clamped = [this](const unsigned int g) {
        return clamps(g);
      };
      if (set.size() < 2 || std::none_of(set.begin(), set.end(), is_clamped))
        return;
      const unsigned int clamped =
        *std::find_if(set.begin(), set.end(), is_clamped);
      const unsigned int other = set[0] == clamped ? set[1] : set[0];
      throw ParameterError(
        bodies.in_file + ": curve " + std::to_string(curve_of_line.at(edge)) +
        " is in '" + use.condition_groups[clamped].first +
        "', clamped in x and y (" + use.condition_groups[clamped].second +
        "), and in '" + use.condition_groups[other].first + "' (" +
        use.condition_groups[other].second +
        "); a clamped curve takes no other condition or load");
    }
  } // namespace



  TwoBodyGmshMeshes
  read_two_body_model(const std::string  &file_name,
                      const CellType      requested_cell_type,
                      const double        mesh_size_factor,
                      const GmshGroupUse &use)
  {
    return TwoBodyReader(file_name, use, requested_cell_type, mesh_size_factor)
      .read();
  }
} // namespace coulomb_adapt
