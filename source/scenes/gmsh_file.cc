#include <deal.II/base/function.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_file.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>

namespace coulomb_adapt
{
  namespace scenes
  {
    namespace
    {
      const std::string scene_path = "Scene/Gmsh";

      // The "group: value" pairs of a Patterns::Map entry, in their order;
      // a group named twice is an error (one value would be dropped).
      std::vector<std::pair<std::string, std::string>>
      group_map(ParameterHandler &prm, const std::string &entry)
      {
        std::vector<std::pair<std::string, std::string>> pairs;
        for (const auto &item :
             Utilities::split_string_list(prm.get(entry), ','))
          {
            const auto key_value = Utilities::split_string_list(item, ':');
            if (key_value.size() != 2 || key_value[0].empty())
              throw ParameterError(scene_path + "/" + entry,
                                   item,
                                   "entries of the form 'group: value'");
            for (const auto &[group, value] : pairs)
              if (group == key_value[0])
                throw ParameterError(scene_path + "/" + entry,
                                     prm.get(entry),
                                     "each group once (group '" + group +
                                       "' appears twice)");
            pairs.emplace_back(key_value[0], key_value[1]);
          }
        return pairs;
      }



      double
      parse_number(const std::string &text,
                   const std::string &entry,
                   const std::string &group,
                   const std::string &allowed)
      {
        std::istringstream in(text);
        double             value;
        std::string        rest;
        if (!(in >> value) || (in >> rest) || !std::isfinite(value))
          throw ParameterError(scene_path + "/" + entry,
                               group + ": " + text,
                               "for group '" + group + "' " + allowed);
        return value;
      }



      // "x", "y", "x y", each optionally "=value" (mm).
      std::array<std::optional<double>, 2>
      parse_fixed_components(const std::string &text, const std::string &group)
      {
        const std::string allowed =
          "the fixed components: 'x', 'y' or 'x y', each optionally with a "
          "prescribed displacement in mm ('y=-0.1'); a wrong component "
          "name or value is not allowed";
        std::array<std::optional<double>, 2> fixed;
        std::istringstream                   in(text);
        std::string                          token;
        unsigned int                         n_tokens = 0;
        while (in >> token)
          {
            ++n_tokens;
            const auto        equal     = token.find('=');
            const std::string component = token.substr(0, equal);
            if (component != "x" && component != "y")
              throw ParameterError(scene_path + "/Fixed components",
                                   group + ": " + text,
                                   "for group '" + group +
                                     "' (unknown component '" + component +
                                     "') " + allowed);
            const unsigned int c = component == "x" ? 0 : 1;
            if (fixed[c])
              throw ParameterError(scene_path + "/Fixed components",
                                   group + ": " + text,
                                   "for group '" + group + "' (component '" +
                                     component + "' twice) " + allowed);
            fixed[c] = equal == std::string::npos ?
                         0. :
                         parse_number(token.substr(equal + 1),
                                      "Fixed components",
                                      group,
                                      allowed);
          }
        if (n_tokens == 0)
          throw ParameterError(scene_path + "/Fixed components",
                               group + ":",
                               "for group '" + group + "' " + allowed);
        return fixed;
      }



      // "tx; ty" (MPa).
      Tensor<1, 2>
      parse_vector(const std::string &text,
                   const std::string &entry,
                   const std::string &group,
                   const std::string &unit)
      {
        const std::string allowed =
          "a vector 'x; y' of two numbers (" + unit + ")";
        const auto parts = Utilities::split_string_list(text, ';');
        if (parts.size() != 2)
          throw ParameterError(scene_path + "/" + entry,
                               group + ": " + text,
                               "for group '" + group + "' " + allowed);
        return Tensor<1, 2>({parse_number(parts[0], entry, group, allowed),
                             parse_number(parts[1], entry, group, allowed)});
      }



      Tensor<1, 2>
      get_vector(ParameterHandler &prm, const std::string &entry)
      {
        const auto v = Utilities::string_to_double(
          Utilities::split_string_list(prm.get(entry)));
        return Tensor<1, 2>({v[0], v[1]});
      }


      // The entries of one body: its surfaces and its body force (the
      // material entries come from declare_body_materials).
      void
      declare_body_entries(ParameterHandler &prm, const unsigned int b)
      {
        prm.enter_subsection("Body " + std::to_string(b));
        {
          prm.declare_entry("Physical surfaces",
                            "body " + std::to_string(b),
                            Patterns::List(Patterns::Anything(), 1),
                            "The physical surfaces that form this body "
                            "(comma-separated names).");
          prm.declare_entry("Density",
                            "0",
                            Patterns::Double(),
                            "Mass density (t/mm^3, e.g. 7.85e-9 for "
                            "steel), >= 0: with 'Gravity' and 'Angular "
                            "velocity' the body force density x "
                            "(g + omega^2 (x - axis)) in N/mm^3.");
          prm.declare_entry("Gravity",
                            "0, 0",
                            Patterns::List(Patterns::Double(), 2, 2),
                            "Acceleration of gravity (x, y) (mm/s^2, "
                            "e.g. 0, -9810).");
          prm.declare_entry("Angular velocity",
                            "0",
                            Patterns::Double(),
                            "Angular velocity omega (rad/s) of the body "
                            "about 'Rotation axis': the centrifugal "
                            "load of a rotating part.");
          prm.declare_entry("Rotation axis",
                            "0, 0",
                            Patterns::List(Patterns::Double(), 2, 2),
                            "Point (x, y) (mm) where the rotation axis, "
                            "perpendicular to the plane, passes.");
        }
        prm.leave_subsection();
      }

      // The conditions and loads per physical group, their rotation
      // centre and the load steps.
      void
      declare_condition_entries(ParameterHandler &prm)
      {
        prm.declare_entry("Fixed components",
                          "",
                          Patterns::Map(Patterns::Anything(),
                                        Patterns::Anything()),
                          "Displacement conditions per physical curve: "
                          "'group: components', the components 'x', 'y' or "
                          "'x y' fixed (zero displacement) or prescribed "
                          "('y=-0.1', mm), e.g. 'base: x y, axis: x, top: "
                          "y=-0.05'. Rollers and symmetry lines fix one "
                          "component.");
        prm.declare_entry("Prescribed rotations",
                          "",
                          Patterns::Map(Patterns::Anything(),
                                        Patterns::Anything()),
                          "Rigid rotations per physical curve: 'group: "
                          "angle' (rad, counterclockwise) about 'Rotation "
                          "centre', e.g. 'shaft bore: 1e-4'. Both "
                          "components are prescribed, linearised (small "
                          "strain): u = angle (-(y - c_y), x - c_x).");
        prm.declare_entry("Rotation centre",
                          "0, 0",
                          Patterns::List(Patterns::Double(), 2, 2),
                          "The point (x, y) (mm) about which the "
                          "'Prescribed rotations' turn.");
        prm.declare_entry("Load steps",
                          "1",
                          Patterns::Integer(1, 1000),
                          "Number of quasi-static load steps: step k of n "
                          "applies k/n of every prescribed displacement "
                          "and rotation, traction, normal pressure and body "
                          "force, carrying the stick/slip history from step "
                          "to step; the initial overlap of the file's "
                          "geometry is there from step 1. 1: the static "
                          "problem.");
        prm.declare_entry("Tractions",
                          "",
                          Patterns::Map(Patterns::Anything(),
                                        Patterns::Anything()),
                          "Uniform tractions per physical curve: 'group: "
                          "tx; ty' (MPa), e.g. 'top: 0; -10'.");
        prm.declare_entry("Normal pressures",
                          "",
                          Patterns::Map(Patterns::Anything(),
                                        Patterns::Anything()),
                          "Pressure per physical curve, following the "
                          "boundary's outward normal n (traction -p n; p > 0 "
                          "presses on the body): 'group: p' (MPa), e.g. "
                          "'outer: 5'.");
        prm.declare_entry("Tangential tractions",
                          "",
                          Patterns::Map(Patterns::Anything(),
                                        Patterns::Anything()),
                          "Tangential traction per physical curve, "
                          "following the boundary's tangent t = (-n_y, n_x) "
                          "(the outward normal n turned counterclockwise: "
                          "counterclockwise around a body's outer boundary, "
                          "clockwise around its holes): 'group: s' (MPa), "
                          "the traction s t, e.g. 'shaft bore: -20' turns a "
                          "shaft counterclockwise at its bore.");
      }
    } // namespace



    void
    GmshFile::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Gmsh");
      {
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "A .geo or .msh file with the physical groups "
                          "named below (by default surfaces 'body 1' "
                          "(upper, slave), 'body 2' and curves 'dirichlet', "
                          "'traction', 'contact'). A relative path in a "
                          "parameter file is looked for beside that file, "
                          "then in the directory the program runs in; with "
                          "-s, in the directory the program runs in.");
        prm.declare_entry("Mesh size factor",
                          "1",
                          Patterns::Double(0),
                          "Factor on the element sizes of a .geo file "
                          "(gmsh's Mesh.MeshSizeFactor); ignored for .msh.");
        declare_condition_entries(prm);
        prm.declare_entry("Contact pair",
                          "contact, contact",
                          Patterns::List(Patterns::Anything(), 2, 2),
                          "The contact pair 'slave group, master group': "
                          "physical curves on the boundary of body 1 (slave) "
                          "and of body 2 (master). One group named twice "
                          "serves both sides, split by the body it bounds.");
        prm.declare_entry("Traction",
                          "0, -10",
                          Patterns::List(Patterns::Double(), 2, 2),
                          "Old syntax, used only if 'Fixed components', "
                          "'Prescribed rotations', 'Tractions', 'Normal "
                          "pressures' and 'Tangential tractions' are all "
                          "empty: uniform traction "
                          "(x, y) on the curves 'traction' (MPa), with "
                          "'dirichlet' clamped.");
        declare_body_materials(prm, 130000., 0.3, 130000., 0.3);
        for (const unsigned int b : {1, 2})
          declare_body_entries(prm, b);
      }
      prm.leave_subsection();
    }



    GmshFile::GmshFile(ParameterHandler &prm,
                       const PlaneModel,
                       const CellType     requested_cell_type,
                       const double       max_dofs,
                       const unsigned int degree,
                       const unsigned int global_refinements)
    {
      prm.enter_subsection("Gmsh");
      {
        materials = parse_body_materials(prm, scene_path);
        GmshGroupUse use;
        for (unsigned int b = 0; b < 2; ++b)
          parse_body(prm, b, use);
        const auto pair = Utilities::split_string_list(prm.get("Contact pair"));
        use.contact_pair  = {{pair[0], pair[1]}};
        use.contact_entry = scene_path + "/Contact pair";
        parse_conditions(prm, use);
        rotation_centre = Point<2>(get_vector(prm, "Rotation centre"));
        n_steps         = prm.get_integer("Load steps");

        const std::string file = prm.get("Mesh file");
        mesh_file              = file;
        if (file.empty())
          throw ParameterError(scene_path + "/Mesh file",
                               file,
                               "the gmsh scene needs a .geo or .msh file");
        // gmsh reads a factor of 0 as "no factor" (1): refuse it rather
        // than mesh at a size the user did not ask for.
        size_factor = prm.get_double("Mesh size factor");
        require_parameter(size_factor > 0,
                          scene_path + "/Mesh size factor",
                          size_factor,
                          "a factor > 0 on the element sizes of the .geo "
                          "file (gmsh ignores 0 and meshes with factor 1)");
        // The program runs on MPI_COMM_WORLD: rank 0 reads the file.
        this->requested_cell_type = requested_cell_type;
        group_use                 = use;
        check_mesh_size_before_meshing(max_dofs, degree, global_refinements);
        geometry = read_two_body_gmsh_geometry(
          file, requested_cell_type, size_factor, use, MPI_COMM_WORLD);
        check_point_supports();
        check_shared_groups();
      }
      prm.leave_subsection();
    }



    // gmsh meshes the file here, before any other check: a small 'Mesh
    // size factor' (1e-4 on blocks.geo) meshed for minutes without a line
    // of output, and 0.03 was refused only after 20 s of meshing, naming
    // 'Maximum number of DoFs'. The probes mesh the file 2^k times coarser,
    // from the k that makes the first probe 1024 times coarser than the
    // file's own sizes (k = 10 for a factor >= 1, more for smaller ones:
    // a first probe at 2^10 times 1e-5 was itself millions of cells) down:
    // the cells grow about 4-fold per step, so a probe whose prediction
    // n 4^k (an overestimate while gmsh's coarsest mesh of the geometry
    // holds it up) is below the limit clears the file, and one with
    // enough cells to predict (2000) refuses it. The examples take 3-5
    // small probes. Every rank takes the same decisions (the reader
    // broadcasts).
    void
    GmshFile::check_mesh_size_before_meshing(
      const double       max_dofs,
      const unsigned int degree,
      const unsigned int global_refinements) const
    {
      const std::string extension =
        std::filesystem::path(mesh_file).extension().string();
      if (max_dofs <= 0 || extension == ".msh" || extension == ".MSH")
        return;
      const double dofs_per_cell =
        (requested_cell_type == CellType::quadrilateral ? 2. : 1.) * degree *
        degree * std::pow(4., global_refinements);
      double    previous_n_cells = -1;
      const int first_k =
        10 +
        std::clamp(static_cast<int>(std::ceil(-std::log2(size_factor))), 0, 50);
      for (int k = first_k; k >= 1; --k)
        {
          std::optional<TwoBodyGmshMeshes> probe;
          try
            {
              probe = read_two_body_gmsh_geometry(mesh_file,
                                                  requested_cell_type,
                                                  size_factor * std::pow(2., k),
                                                  group_use,
                                                  MPI_COMM_WORLD);
            }
          catch (const std::exception &)
            {
              // A size the geometry cannot be meshed with: finer probes.
              continue;
            }
          const double n_cells =
            probe->meshes[0].cells.size() + probe->meshes[1].cells.size();
          const double predicted = n_cells * std::pow(4., k) * dofs_per_cell;
          if (predicted <= max_dofs)
            return;
          // Transfinite lines: the factor does not change these cells, the
          // probes are the file's own mesh, which the checks after meshing
          // judge.
          if (n_cells >= 2000 && n_cells == previous_n_cells)
            return;
          // Refused only where the cells are seen to follow the factor, and
          // with a margin: one transfinite body beside a free one grows
          // less than 4-fold per step (a review measured a prediction 35 %
          // high).
          if (n_cells >= 2000 && previous_n_cells > 0 &&
              n_cells >= 2.5 * previous_n_cells && predicted > 2 * max_dofs)
            {
              std::ostringstream s;
              s << "the file's meshes would have about " << std::setprecision(2)
                << predicted << " DoFs (meshed " << std::pow(2., k)
                << " times coarser they have " << n_cells
                << " cells), above 'Adaptation/Maximum number of DoFs' ("
                << max_dofs
                << "): raise the factor, or that limit if the machine has "
                   "the memory (about 1 kB per DoF)";
              throw ParameterError(scene_path + "/Mesh size factor",
                                   format_value(size_factor),
                                   s.str());
            }
          previous_n_cells = n_cells;
        }
    }



    // Body @p b's surfaces and body force (a density where an
    // acceleration is given: the force is density x acceleration).
    void
    GmshFile::parse_body(ParameterHandler  &prm,
                         const unsigned int b,
                         GmshGroupUse      &use)
    {
      const std::string body = "Body " + std::to_string(b + 1);
      const std::string path = scene_path + "/" + body;
      prm.enter_subsection(body);
      {
        use.body_surfaces[b] =
          Utilities::split_string_list(prm.get("Physical surfaces"));
        use.body_entries[b] = path + "/Physical surfaces";
        BodyForce &f        = body_forces[b];
        f.density           = prm.get_double("Density");
        f.gravity           = get_vector(prm, "Gravity");
        f.angular_velocity  = prm.get_double("Angular velocity");
        f.axis              = Point<2>(get_vector(prm, "Rotation axis"));
        require_parameter(f.density >= 0,
                          path + "/Density",
                          f.density,
                          "a mass density >= 0 (t/mm^3)");
        if (f.density == 0 && (f.gravity.norm() > 0 || f.angular_velocity != 0))
          throw ParameterError(path + "/Density",
                               "0",
                               "a density > 0 where 'Gravity' or "
                               "'Angular velocity' is given (the body "
                               "force is density x acceleration)");
      }
      prm.leave_subsection();
    }



    // The conditions of each group, from the entries (or else the
    // old syntax), and which groups clamp both components.
    void
    GmshFile::parse_conditions(ParameterHandler &prm, GmshGroupUse &use)
    {
      parse_condition_entries(prm, use);
      if (conditions.empty())
        {
          // The old syntax: the fixed groups of GmshGroupUse's defaults.
          use.condition_groups            = GmshGroupUse().condition_groups;
          conditions["dirichlet"].fixed   = {{0., 0.}};
          conditions["traction"].traction = get_vector(prm, "Traction");
          conditions["traction"].loaded   = true;
        }
      else if (prm.get("Traction") != "0, -10")
        throw ParameterError(scene_path + "/Traction",
                             prm.get("Traction"),
                             "the default: the old 'Traction' entry is not "
                             "used with 'Fixed components', 'Prescribed "
                             "rotations', 'Tractions', 'Normal pressures' "
                             "or 'Tangential tractions' (give the traction "
                             "in "
                             "'Tractions = group: tx; ty')");
      for (const auto &[group, c] : conditions)
        {
          if (c.rotation && c.loaded)
            throw ParameterError(
              scene_path + "/Prescribed rotations",
              group + ": ...",
              "loads only on curves whose displacement is not prescribed "
              "(group '" +
                group +
                "' also has a traction or pressure, which would "
                "have no effect)");
          if (c.fixed[0] && c.fixed[1] && c.loaded)
            throw ParameterError(
              scene_path + "/Fixed components",
              group + ": x y",
              "loads only on curves that are not fixed in both components "
              "(group '" +
                group +
                "' also has a traction or pressure, which would "
                "have no effect)");
          if (c.fixed[0] && c.fixed[1] && *c.fixed[0] == 0 && *c.fixed[1] == 0)
            use.clamped_groups.insert(group);
        }
    }



    // Each group's conditions, from the entries in turn; a group
    // keeps the entry that named it first for messages.
    void
    GmshFile::parse_condition_entries(ParameterHandler &prm, GmshGroupUse &use)
    {
      use.condition_groups.clear();
      use.clamped_groups.clear();
      const auto add_group = [&](const std::string &group,
                                 const std::string &entry) {
        for (const auto &[name, first_entry] : use.condition_groups)
          if (name == group)
            return;
        use.condition_groups.emplace_back(group, scene_path + "/" + entry);
      };
      for (const auto &[group, value] : group_map(prm, "Fixed components"))
        {
          conditions[group].fixed = parse_fixed_components(value, group);
          add_group(group, "Fixed components");
          use.point_groups_allowed.insert(group);
        }
      for (const auto &[group, value] : group_map(prm, "Prescribed rotations"))
        {
          if (conditions.count(group) > 0)
            throw ParameterError(
              scene_path + "/Prescribed rotations",
              group + ": " + value,
              "groups without 'Fixed components' (group '" + group +
                "' has both; a rotation prescribes both components)");
          conditions[group].rotation = parse_number(value,
                                                    "Prescribed rotations",
                                                    group,
                                                    "an angle (rad)");
          add_group(group, "Prescribed rotations");
        }
      for (const auto &[group, value] : group_map(prm, "Tractions"))
        {
          conditions[group].traction =
            parse_vector(value, "Tractions", group, "MPa");
          conditions[group].loaded = true;
          add_group(group, "Tractions");
        }
      for (const auto &[group, value] : group_map(prm, "Normal pressures"))
        {
          conditions[group].pressure = parse_number(value,
                                                    "Normal pressures",
                                                    group,
                                                    "a pressure p (MPa)");
          conditions[group].loaded   = true;
          add_group(group, "Normal pressures");
        }
      for (const auto &[group, value] : group_map(prm, "Tangential tractions"))
        {
          conditions[group].shear  = parse_number(value,
                                                 "Tangential tractions",
                                                 group,
                                                 "a tangential traction s "
                                                  "(MPa)");
          conditions[group].loaded = true;
          add_group(group, "Tangential tractions");
        }
    }



    // A point support holds its nodes in place (no prescribed value, no
    // load: a point has no length to carry one).
    void
    GmshFile::check_point_supports()
    {
      for (const auto &support : geometry.point_supports)
        {
          const GroupConditions &c = conditions[support.group];
          if (c.loaded)
            throw ParameterError(
              "gmsh file '" + mesh_file + "': '" + support.group +
              "' is a physical point, not a physical curve: tractions, "
              "normal pressures and tangential tractions act on boundary "
              "curves");
          for (unsigned int k = 0; k < 2; ++k)
            if (c.fixed[k] && *c.fixed[k] != 0)
              throw ParameterError(
                scene_path + "/Fixed components",
                support.group + ": ...",
                "zero displacement ('x', 'y' or 'x y') on physical points "
                "('" +
                  support.group +
                  "' is one); prescribed values on curves only");
        }
    }



    // Groups that share lines must agree on what they prescribe; a
    // rotation prescribes both components, so it shares curves with no
    // other condition or load.
    void
    GmshFile::check_shared_groups()
    {
      for (const auto &[id, groups] : geometry.groups_of_boundary_id)
        for (const auto &g : groups)
          for (const auto &h : groups)
            if (g != h && conditions[g].rotation &&
                (conditions[h].rotation || conditions[h].fixed[0] ||
                 conditions[h].fixed[1] || conditions[h].loaded))
              throw ParameterError(
                "gmsh file '" + mesh_file + "': groups '" + g + "' (" +
                scene_path + "/Prescribed rotations) and '" + h +
                "' share curves; a prescribed rotation fixes both "
                "components, so no other displacement condition or load "
                "may act there");
      for (const auto &[id, groups] : geometry.groups_of_boundary_id)
        for (unsigned int c = 0; c < 2; ++c)
          for (const auto &g : groups)
            for (const auto &h : groups)
              if (conditions[g].fixed[c] && conditions[h].fixed[c] &&
                  *conditions[g].fixed[c] != *conditions[h].fixed[c])
                throw ParameterError(
                  "gmsh file '" + mesh_file + "': groups '" + g + "' and '" +
                  h + "' (" + scene_path +
                  "/Fixed components) share curves and prescribe "
                  "different " +
                  (c == 0 ? "x" : "y") + " displacements there");
    }



    std::vector<std::string>
    GmshFile::load_entries() const
    {
      return {"Scene/Gmsh/Fixed components",
              "Scene/Gmsh/Prescribed rotations",
              "Scene/Gmsh/Tractions",
              "Scene/Gmsh/Normal pressures",
              "Scene/Gmsh/Tangential tractions",
              "Scene/Gmsh/Traction",
              "Scene/Gmsh/Body 1 and 2/Density, Gravity, Angular velocity"};
    }



    std::string
    GmshFile::name() const
    {
      return "gmsh";
    }



    std::string
    GmshFile::mesh_source() const
    {
      return "gmsh file '" + mesh_file + "': ";
    }



    unsigned int
    GmshFile::n_load_steps() const
    {
      return n_steps;
    }



    void
    GmshFile::set_load_step(const unsigned int step) const
    {
      load_fraction = double(step) / n_steps;
    }



    void
    GmshFile::create_coarse_mesh(const unsigned int body,
                                 const CellType,
                                 Triangulation<2> &tria) const
    {
      geometry.meshes[body].create_triangulation(tria);
      attach_circle_manifolds(geometry.circle_centres, tria);
      attach_curve_manifolds(geometry.sampled_curves, tria);
    }
  } // namespace scenes
} // namespace coulomb_adapt
