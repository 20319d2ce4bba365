#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/hertz.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace coulomb_adapt
{
  namespace scenes
  {
    namespace
    {
      constexpr types::manifold_id arc_manifold_id = 1;
    }



    void
    Hertz::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Hertz");
      {
        prm.declare_entry("Radius",
                          "100",
                          Patterns::Double(0),
                          "Radius R of the half disc (mm).");
        prm.declare_entry("Line load",
                          "1000",
                          Patterns::Double(0),
                          "Total load P' per unit thickness pressing the "
                          "disc down (N/mm), applied as a uniform traction "
                          "P'/(2R) on its flat top.");
        prm.declare_entry("Hold axis",
                          "true",
                          Patterns::Bool(),
                          "Fix the horizontal displacement of the disc's "
                          "nodes on its axis x = 0 (exact by symmetry); "
                          "needed without friction, where nothing else "
                          "holds the disc sideways.");
        prm.declare_entry("Block width",
                          "200",
                          Patterns::Double(0),
                          "Width 2L of the block (mm).");
        prm.declare_entry("Block height",
                          "100",
                          Patterns::Double(0),
                          "Height H of the block (mm).");
        prm.declare_entry("Block subdivisions",
                          "2, 1",
                          Patterns::List(Patterns::Integer(1), 2, 2),
                          "Coarse cells of the block in x and y.");
        prm.declare_entry("Contact mesh size",
                          "0.1",
                          Patterns::Double(0),
                          "Element size near the first contact point, in "
                          "units of the Hertz half-width a (0.1: 20 "
                          "elements across the contact width). 0 disables "
                          "the grading (quadrilaterals then need 'Mesh/"
                          "Global refinements' >= 1). Global refinements "
                          "divide it "
                          "further. Refused when the graded meshes would "
                          "exceed 'Adaptation/Maximum number of DoFs'.");
        prm.declare_entry("Refined zone size",
                          "1.5",
                          Patterns::Double(0),
                          "Radius of the zone around the first contact "
                          "point that gets the contact mesh size, in units "
                          "of a; the mesh coarsens gradually outside it.");
        declare_body_materials(prm, 130000., 0.3, 130000., 0.3);
      }
      prm.leave_subsection();

      prm.enter_subsection("Cattaneo");
      {
        prm.declare_entry("Normal displacement",
                          "0.044",
                          Patterns::Double(0),
                          "Downward displacement of the disc's top (mm), "
                          "imposed in load step 1 by a rigid holder that "
                          "keeps the disc from rotating. The default gives "
                          "a normal load P' of about 1000 N/mm with the "
                          "Hertz defaults; the solver reports P' and Q as "
                          "the contact force.");
        prm.declare_entry("Tangential displacement",
                          "0.011",
                          Patterns::Double(),
                          "Sideways displacement of the disc's top (mm) at "
                          "the end of the load path, reached in "
                          "'Tangential load steps' equal steps after the "
                          "normal one. The default gives Q of about "
                          "0.6 mu P' for mu = 0.3.");
        prm.declare_entry("Tangential load steps",
                          "5",
                          Patterns::Integer(1, 1000),
                          "Number of quasi-static steps in which the "
                          "tangential load grows to Q.");
      }
      prm.leave_subsection();
    }



    Hertz::Hertz(ParameterHandler &prm,
                 const Parameters &parameters,
                 const bool        cattaneo)
      : cattaneo(cattaneo)
      , normal_displacement(0)
      , tangential_displacement(0)
      , n_tangential_steps(0)
      , plane_model(parameters.finite_elements.plane_model)
    {
      if (cattaneo)
        {
          prm.enter_subsection("Cattaneo");
          normal_displacement     = prm.get_double("Normal displacement");
          tangential_displacement = prm.get_double("Tangential displacement");
          n_tangential_steps      = prm.get_integer("Tangential load steps");
          // Without it the disc does not press on the block: no contact
          // force, no strain, and a tangential displacement of the holder
          // only moves the disc rigidly; the relative error is then a
          // ratio of round-off to round-off.
          require_parameter(normal_displacement > 0,
                            "Scene/Cattaneo/Normal displacement",
                            normal_displacement,
                            "must be > 0: the disc must be pressed onto the "
                            "block before the tangential load (0 leaves no "
                            "contact force and no strain)");
          prm.leave_subsection();
        }
      prm.enter_subsection("Hertz");
      {
        const std::string path = "Scene/Hertz";
        radius                 = prm.get_double("Radius");
        // R = 0 is a point, whose Hertz half-width a = 0 would grade the
        // mesh towards it without end.
        require_parameter(radius > 0,
                          path + "/Radius",
                          radius,
                          "must be > 0 (mm)");
        line_load = prm.get_double("Line load");
        // A tangential load must not be carried by a support on the axis.
        hold_axis           = prm.get_bool("Hold axis") && !cattaneo;
        block_width         = prm.get_double("Block width");
        block_height        = prm.get_double("Block height");
        block_subdivisions  = get_subdivisions(prm, "Block subdivisions", path);
        contact_mesh_factor = prm.get_double("Contact mesh size");
        refined_zone_factor = prm.get_double("Refined zone size");
        materials           = parse_body_materials(prm, path);
      }
      prm.leave_subsection();
      // Hertz's half-width a assumes a << R; at a >= R its contact zone
      // would be wider than the disc, and the grading towards it and the
      // reference pressure mean nothing (a probe's 1e10 N/mm stopped on
      // "selects no node", a hint for mesh files).
      if (!cattaneo && contact_half_width() >= radius)
        {
          std::ostringstream s;
          s << std::setprecision(3)
            << "Hertz's contact half-width for this load would be a = "
            << contact_half_width()
            << " mm, not small against the radius R = " << radius
            << " mm (the formula assumes a << R; at a >= R the zone would be "
               "wider than the disc). Allowed: a line load below "
            << line_load * std::pow(radius / contact_half_width(), 2)
            << " N/mm (a = R) with these materials; a few % of that keeps "
               "a / R small";
          throw ParameterError("Scene/Hertz/Line load",
                               Patterns::Tools::Convert<double>::to_string(
                                 line_load),
                               s.str());
        }
      check_initial_mesh_size(parameters);
    }



    // The graded meshes' size follows from the sizes alone: the refined
    // zone of radius z a around the origin is a half disc in each body,
    // filled with elements of size h = c a, so each body gets about
    // (pi / 2) (z / c)^2 cells of area h^2 whatever a is (gmsh's triangles
    // of edge h have the area sqrt(3) / 4 h^2: 4 / sqrt(3) times as many).
    // Local refinement halves the coarse cells until their edges are at
    // most h, so the quadrilaterals' edges end between h / 2 and h: the
    // edge they reach follows from the coarse cell at the origin. The
    // cells outside the zone are left out, so the count is a lower bound:
    // a run it lets through may still reach the limit, one it refuses
    // would exceed it. Each global refinement multiplies the cells by 4;
    // a cell carries about 2 p^2 DoFs (quadrilaterals) or p^2 (triangles).
    // Before: 0.001 printed nothing and grew to 6.7 GB in 55 s.
    void
    Hertz::check_initial_mesh_size(const Parameters &parameters) const
    {
      const bool quadrilaterals =
        parameters.mesh.cell_type == CellType::quadrilateral;
      // Ungraded quadrilaterals are the coarse meshes themselves: the
      // disc's is deal.II's half ball of 4 cells, with no node on the axis
      // for 'Hold axis' and, without it, no contact node facing the block
      // (found by a probe: the run stopped on "selects no node" with a
      // hint about mesh files).
      if (quadrilaterals && contact_mesh_factor == 0 &&
          parameters.mesh.global_refinements == 0)
        throw ParameterError(
          "Scene/Hertz/Contact mesh size",
          "0",
          "with quadrilaterals and 'Mesh/Global refinements' = 0 the disc "
          "would be its coarse mesh of 4 cells, which has no node on its "
          "axis x = 0 and no contact node facing the block. Allowed: a "
          "contact mesh size > 0 (the default 0.1 grades the mesh towards "
          "the contact), or 'Mesh/Global refinements' >= 1, or 'Mesh/Cell "
          "type' = triangle");
      if (contact_mesh_factor == 0)
        return;
      const double a      = contact_half_width();
      const double h      = contact_mesh_size();
      const double zone   = refined_zone_factor * a;
      const double p      = parameters.finite_elements.degree;
      double       n_dofs = 0;
      for (unsigned int b = 0; b < 2; ++b)
        {
          double edge = h;
          if (quadrilaterals)
            {
              Triangulation<2> coarse;
              create_coarse_mesh(b, CellType::quadrilateral, coarse);
              double coarse_edge = 0;
              for (const auto &cell : coarse.active_cell_iterators())
                if (cell->point_inside(Point<2>()) ||
                    cell->center().distance(Point<2>()) <
                      zone + cell->diameter())
                  for (const auto &face : cell->face_iterators())
                    coarse_edge = std::max(coarse_edge, face->measure());
              while (coarse_edge > h)
                coarse_edge /= 2;
              edge = coarse_edge > 0 ? coarse_edge : h;
            }
          const double cells = numbers::PI / 2 * (zone / edge) * (zone / edge) *
                               (quadrilaterals ? 1. : 4. / std::sqrt(3.));
          n_dofs += cells * (quadrilaterals ? 2. : 1.) * p * p;
        }
      n_dofs *= std::pow(4., parameters.mesh.global_refinements);
      if (n_dofs <= parameters.adaptation.max_dofs)
        return;
      // The count goes as 1 / c^2 (in steps of 4 for quadrilaterals).
      const double smallest =
        contact_mesh_factor *
        std::sqrt(n_dofs / parameters.adaptation.max_dofs);
      std::ostringstream s;
      s << std::setprecision(3) << "the graded meshes would have at least "
        << n_dofs << " DoFs (elements of " << h << " mm in a zone of " << zone
        << " mm around the first contact point, "
        << (quadrilaterals ? "quadrilaterals" : "triangles") << " of degree "
        << p << ", " << parameters.mesh.global_refinements
        << " global refinements), above 'Adaptation/Maximum number of "
           "DoFs' ("
        << parameters.adaptation.max_dofs
        << "). Allowed: 0 (no grading) or at least about " << smallest
        << " with these settings; or a smaller 'Scene/Hertz/Refined zone "
           "size', or a larger 'Adaptation/Maximum number of DoFs' if the "
           "machine has the memory (about 1 kB per DoF)";
      throw ParameterError("Scene/Hertz/Contact mesh size",
                           Patterns::Tools::Convert<double>::to_string(
                             contact_mesh_factor),
                           s.str());
    }



    std::vector<std::string>
    Hertz::load_entries() const
    {
      if (cattaneo)
        return {"Scene/Cattaneo/Normal displacement",
                "Scene/Cattaneo/Tangential displacement"};
      return {"Scene/Hertz/Line load"};
    }



    std::string
    Hertz::name() const
    {
      return cattaneo ? "cattaneo" : "hertz";
    }



    std::map<std::string, double>
    Hertz::reference_values() const
    {
      return {{"hertz_half_width", contact_half_width()},
              {"hertz_peak_pressure", peak_pressure()},
              {"line_load", line_load},
              {"radius", radius}};
    }



    unsigned int
    Hertz::n_load_steps() const
    {
      return 1 + n_tangential_steps;
    }



    void
    Hertz::set_load_step(const unsigned int step) const
    {
      tangential_fraction =
        n_tangential_steps == 0 ? 0. : double(step - 1) / n_tangential_steps;
    }



    double
    Hertz::load_increment_ratio(const unsigned int step) const
    {
      return (cattaneo && step >= 3) ? 1. : 0.;
    }



    void
    Hertz::create_coarse_mesh(const unsigned int body,
                              const CellType     cell_type,
                              Triangulation<2>  &tria) const
    {
      using namespace boundary_ids;
      // Triangles: gmsh meshes both bodies with the size field of the
      // contact zone (simplices cannot be refined locally in deal.II 9.4).
      if (cell_type == CellType::triangle)
        {
          triangle_meshes()[body].create_triangulation(tria);
          if (body == 0)
            {
              tria.set_manifold(arc_manifold_id,
                                SphericalManifold<2>(Point<2>(0, radius)));
              for (const auto &cell : tria.active_cell_iterators())
                for (const auto &face : cell->face_iterators())
                  if (face->at_boundary() && face->boundary_id() == contact)
                    face->set_manifold_id(arc_manifold_id);
            }
          return;
        }

      if (body == 1)
        {
          make_rectangle(tria,
                         Point<2>(-block_width / 2, -block_height),
                         Point<2>(block_width / 2, 0),
                         block_subdivisions,
                         {{traction_free, traction_free, dirichlet, contact}},
                         cell_type);
          return;
        }

      // Quadrilaterals: deal.II's half ball (the half x > 0 of the disc)
      // turned by -90 degrees so that its arc points down, then lifted so
      // that its lowest point is the origin.
      Triangulation<2> &quads = tria;
      const Point<2>    centre(0, radius);
      tria.clear();
      GridGenerator::half_hyper_ball(quads, Point<2>(), radius);
      GridTools::rotate(-numbers::PI / 2, quads);
      GridTools::shift(Tensor<1, 2>({0., radius}), quads);
      quads.reset_all_manifolds();
      for (const auto &cell : quads.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const bool on_flat_top =
                std::abs(face->center()[1] - radius) < 1e-8 * radius;
              face->set_boundary_id(on_flat_top ? traction : contact);
              if (!on_flat_top)
                face->set_manifold_id(arc_manifold_id);
            }
      tria.set_manifold(arc_manifold_id, SphericalManifold<2>(centre));
    }



    // The .geo text of both bodies, with a mesh size field that is
    // contact_mesh_size() within the refined zone around the origin and
    // grows linearly to the coarse size away from it.
    const std::array<CoarseMeshData, 2> &
    Hertz::triangle_meshes() const
    {
      if (!gmsh_meshes)
        {
          const double a = contact_half_width();
          // Away from the contact the larger of the two bodies sets the
          // size: with the disc's radius alone a small disc on the default
          // block gave 7.4e5 triangles (R = 1 mm). Without grading
          // ('Contact mesh size' = 0) the size is the same everywhere: gmsh
          // aborted on a zero minimum size.
          const double h_max =
            std::max(radius, std::min(block_width / 2, block_height)) / 4;
          const double       h_min = contact_mesh_factor > 0 ?
                                       std::min(contact_mesh_size(), h_max) :
                                       h_max;
          const double       zone  = refined_zone_factor * a;
          std::ostringstream geo;
          geo << std::setprecision(17) << "R = " << radius
              << "; L = " << block_width / 2 << "; H = " << block_height
              << ";\n"
              << "Point(1) = {0, R, 0};  Point(2) = {-R, R, 0};\n"
              << "Point(3) = {0, 0, 0};  Point(4) = {R, R, 0};\n"
              << "Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4};\n"
              << "Line(3) = {4, 1}; Line(9) = {1, 2};\n"
              << "Curve Loop(1) = {1, 2, 3, 9}; Plane Surface(1) = {1};\n"
              // The axis, embedded so that it is a line of nodes: 'Hold
              // axis' constrains the nodes on it.
              << "Line(10) = {1, 3}; Line{10} In Surface{1};\n"
              << "Point(5) = {-L, -H, 0}; Point(6) = {L, -H, 0};\n"
              << "Point(7) = {L, 0, 0};   Point(8) = {-L, 0, 0};\n"
              << "Point(9) = {0, 0, 0};\n"
              << "Line(4) = {5, 6}; Line(5) = {6, 7}; Line(6) = {7, 9};\n"
              << "Line(7) = {9, 8}; Line(8) = {8, 5};\n"
              << "Curve Loop(2) = {4, 5, 6, 7, 8}; Plane Surface(2) = {2};\n"
              << "Physical Surface(\"body 1\") = {1};\n"
              << "Physical Surface(\"body 2\") = {2};\n"
              << "Physical Curve(\"dirichlet\") = {4};\n"
              << "Physical Curve(\"traction\") = {3, 9};\n"
              << "Physical Curve(\"contact\") = {1, 2, 6, 7};\n"
              << "Field[1] = Distance; Field[1].PointsList = {3, 9};\n"
              << "Field[2] = Threshold; Field[2].InField = 1;\n"
              << "Field[2].SizeMin = " << h_min << ";\n"
              << "Field[2].SizeMax = " << h_max << ";\n"
              << "Field[2].DistMin = " << zone << ";\n"
              << "Field[2].DistMax = " << zone + 4 * (h_max - h_min) << ";\n"
              << "Background Field = 2;\n"
              << "Mesh.MeshSizeExtendFromBoundary = 0;\n"
              << "Mesh.MeshSizeFromPoints = 0;\n"
              << "Mesh.MeshSizeFromCurvature = 0;\n";
          const std::string file =
            (std::filesystem::temp_directory_path() /
             ("coulomb-adapt-hertz-" + std::to_string(::getpid()) + ".geo"))
              .string();
          {
            std::ofstream out(file);
            out << geo.str();
          }
          gmsh_meshes = std::make_shared<std::array<CoarseMeshData, 2>>(
            read_two_body_gmsh_file(file, CellType::triangle, 1.0));
          std::filesystem::remove(file);
        }
      return *gmsh_meshes;
    }



    std::unique_ptr<Scene>
    Hertz::with_coarser_graded_meshes(const unsigned int k) const
    {
      if (contact_mesh_factor == 0)
        return nullptr;
      auto coarser = std::make_unique<Hertz>(*this);
      coarser->contact_mesh_factor *= std::pow(2., k);
      coarser->gmsh_meshes.reset(); // meshed again with the coarser size
      return coarser;
    }



    double
    Hertz::contact_mesh_size() const
    {
      return contact_mesh_factor * contact_half_width();
    }



    void
    Hertz::refine_initial_mesh(const unsigned int, Triangulation<2> &tria) const
    {
      if (contact_mesh_factor > 0)
        refine_towards_point(tria,
                             Point<2>(),
                             refined_zone_factor * contact_half_width(),
                             contact_mesh_size());
    }



    BodyDescription
    Hertz::describe_body(const unsigned int body) const
    {
      BodyDescription d;
      d.material            = materials[body];
      d.contact_boundary_id = boundary_ids::contact;
      if (body == 0)
        {
          d.name = "half disc";
          // The ends of the contact zone only: the holder's edges of
          // 'cattaneo' have always been left out (the default would count
          // them as clamped); whether they matter has not been measured.
          d.singular_junction_parts = {boundary_ids::contact};
          if (cattaneo)
            // The disc's top is moved by a rigid holder: down by the normal
            // displacement, then sideways in steps. The holder keeps the
            // disc from rotating (a shear load on its free top would tip it
            // over: its moment Q R dwarfs what the contact zone resists).
            d.dirichlet.push_back(
              {boundary_ids::traction,
               ComponentMask(2, true),
               std::make_shared<FunctionFromFunctionObjects<2>>(
                 std::vector<std::function<double(const Point<2> &)>>{
                   [this](const Point<2> &) {
                     return tangential_fraction * tangential_displacement;
                   },
                   [this](const Point<2> &) {
                     return -normal_displacement;
                   }})});
          else
            d.tractions.push_back(
              {boundary_ids::traction,
               [this](const Point<2> &, const Tensor<1, 2> &) {
                 return Tensor<1, 2>({0., -line_load / (2. * radius)});
               }});
          if (hold_axis)
            d.point_constraints.push_back(
              // The axis above the contact point (contact nodes stay free).
              {[r = radius](const Point<2> &x) {
                 return std::abs(x[0]) < 1e-10 * r && x[1] > 1e-10 * r;
               },
               ComponentMask(std::vector<bool>{true, false}),
               std::array<Point<2>, 2>{{Point<2>(0, 0), Point<2>(0, radius)}}});
        }
      else
        {
          d.name = "block";
          d.dirichlet.push_back(
            {boundary_ids::dirichlet,
             ComponentMask(2, true),
             std::make_shared<Functions::ZeroFunction<2>>(2)});
        }
      return d;
    }



    double
    Hertz::contact_half_width() const
    {
      // 1/E* = sum of (1 - nu^2)/E in plane strain, 1/E in plane stress.
      double compliance = 0;
      for (const auto &m : materials)
        compliance += (plane_model == PlaneModel::plane_strain ?
                         1. - m.poissons_ratio * m.poissons_ratio :
                         1.) /
                      m.youngs_modulus;
      const double effective_modulus = 1. / compliance;
      return std::sqrt(4. * line_load * radius /
                       (numbers::PI * effective_modulus));
    }



    double
    Hertz::peak_pressure() const
    {
      return 2. * line_load / (numbers::PI * contact_half_width());
    }
  } // namespace scenes
} // namespace coulomb_adapt
