// Red refinement of gmsh's meshes ('Adaptation/Remeshing split above
// cells', adaptation/triangle_split.h): a large body is meshed by gmsh at
// 2^k times the planned sizes and each triangle split into 4 at its edges'
// midpoints, k times.
//
// First the split itself, on gmsh meshes of the scenes' geometries (each
// body remeshed as the remesher does, then split k times), against the
// unsplit mesh:
//  - 4^k times its cells, and conforming: every edge in one or two cells,
//    the edges in one cell exactly the boundary lines (a hanging vertex or
//    a midpoint made twice would leave edges in one cell that are no
//    boundary line), V - E + F unchanged, every vertex in a cell, and
//    deal.II builds a triangulation of it;
//  - each boundary id's total length and the area those of the unsplit
//    mesh to 1e-12 where the boundary is straight (blocks); on the circles
//    and splines of the press fit every vertex of a curved boundary line
//    lies on the curve (a circle to 1e-9 of its radius, a spline's
//    manifold to 1e-9 mm; a straight midpoint would be off by the chord's
//    sag, ~1e-3 mm), so the curved lengths grow towards the arcs';
//  - every child similar to its parent: the smallest angle of each cell is
//    its ancestor's to 1e-10 rad (cells that touch a curved boundary
//    excepted: their midpoints moved onto the curve), so the mesh's
//    smallest angle is gmsh's;
//  - the interior (symmetry) line stays a chain of edges of its length,
//    and the point supports stay vertices.
// Then whole adaptive runs with a low threshold (so that the remeshed
// bodies are split), checked against independent truth:
//  - the quarter press fit, P1: every slave node in contact, the initial
//    overlap delta, the nodal pressures within 1 % of Lame's (the bound of
//    tests/press_fit_adapted_p1; the contact size cap still acts);
//  - blocks: the contact force on the upper block equals its load
//    (1000 N/mm normal, 0 tangential) to 1e-10.
// 1 and 2 ranks print the same.

#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/adaptation/gmsh_remesher.h>
#include <coulomb_adapt/adaptation/triangle_split.h>
#include <coulomb_adapt/scenes/curve_manifold.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "lame_press_fit.h"
#include "program_run.h"

#include <limits>
#include <map>
#include <set>

using namespace coulomb_adapt;

namespace
{
  using Edge = std::pair<unsigned int, unsigned int>;

  Edge
  edge(const unsigned int a, const unsigned int b)
  {
    return std::minmax(a, b);
  }

  // The smallest angle of a triangle.
  double
  min_angle(const CoarseMeshData &mesh, const CellData<2> &cell)
  {
    double result = numbers::PI;
    for (unsigned int v = 0; v < 3; ++v)
      {
        const Point<2>    &x = mesh.vertices[cell.vertices[v]];
        const Tensor<1, 2> u = mesh.vertices[cell.vertices[(v + 1) % 3]] - x,
                           w = mesh.vertices[cell.vertices[(v + 2) % 3]] - x;
        result =
          std::min(result,
                   std::abs(std::atan2(u[0] * w[1] - u[1] * w[0], u * w)));
      }
    return result;
  }

  struct Conformity
  {
    bool                                 conforming = true;
    long                                 euler      = 0; // V - E + F
    double                               area       = 0;
    std::map<types::boundary_id, double> lengths;
  };

  Conformity
  conformity(const CoarseMeshData &mesh)
  {
    Conformity               result;
    std::map<Edge, unsigned> n_cells_at;
    std::vector<bool>        used(mesh.vertices.size(), false);
    for (const auto &cell : mesh.cells)
      {
        for (unsigned int v = 0; v < 3; ++v)
          {
            ++n_cells_at[edge(cell.vertices[v], cell.vertices[(v + 1) % 3])];
            used[cell.vertices[v]] = true;
          }
        const Tensor<1, 2> u = mesh.vertices[cell.vertices[1]] -
                               mesh.vertices[cell.vertices[0]],
                           w = mesh.vertices[cell.vertices[2]] -
                               mesh.vertices[cell.vertices[0]];
        const double area = 0.5 * (u[0] * w[1] - u[1] * w[0]);
        result.conforming = result.conforming && area > 0;
        result.area += area;
      }
    std::set<Edge> boundary;
    for (const auto &line : mesh.boundary_lines.boundary_lines)
      {
        boundary.insert(edge(line.vertices[0], line.vertices[1]));
        result.lengths[line.boundary_id] +=
          mesh.vertices[line.vertices[0]].distance(
            mesh.vertices[line.vertices[1]]);
      }
    for (const auto &[e, n] : n_cells_at)
      result.conforming =
        result.conforming && n <= 2 && (n == 1) == (boundary.count(e) > 0);
    result.conforming =
      result.conforming &&
      boundary.size() == mesh.boundary_lines.boundary_lines.size() &&
      std::all_of(used.begin(), used.end(), [](const bool u) { return u; });
    result.euler =
      long(mesh.vertices.size()) - long(n_cells_at.size()) + mesh.cells.size();
    return result;
  }

  // The largest distance of a vertex of a curved boundary line from its
  // curve, relative to the circle's radius or in mm on a spline.
  double
  distance_from_curves(const CoarseMeshData   &mesh,
                       const Triangulation<2> &geometry,
                       const CoarseMeshData   &unsplit)
  {
    // The circles' radii, from gmsh's nodes on them (concentric circles
    // may share a manifold).
    std::map<types::manifold_id, std::vector<double>> radii;
    for (const auto &line : unsplit.boundary_lines.boundary_lines)
      if (const auto *sphere = dynamic_cast<const SphericalManifold<2> *>(
            &geometry.get_manifold(line.manifold_id)))
        {
          auto        &known = radii[line.manifold_id];
          const double r =
            sphere->center.distance(unsplit.vertices[line.vertices[0]]);
          if (std::none_of(known.begin(), known.end(), [&](const double q) {
                return std::abs(q / r - 1) < 1e-9;
              }))
            known.push_back(r);
        }
    double largest = 0;
    for (const auto &line : mesh.boundary_lines.boundary_lines)
      if (line.manifold_id != numbers::flat_manifold_id)
        for (const unsigned int v : line.vertices)
          {
            const Point<2>    &x = mesh.vertices[v];
            const Manifold<2> &manifold =
              geometry.get_manifold(line.manifold_id);
            if (const auto *sphere =
                  dynamic_cast<const SphericalManifold<2> *>(&manifold))
              {
                double nearest = std::numeric_limits<double>::max();
                for (const double r : radii.at(line.manifold_id))
                  nearest =
                    std::min(nearest,
                             std::abs(sphere->center.distance(x) / r - 1));
                largest = std::max(largest, nearest);
              }
            else
              largest = std::max(largest,
                                 dynamic_cast<const CurveManifold &>(manifold)
                                   .project(x)
                                   .distance(x));
          }
    return largest;
  }

  void
  check_split(const std::string       &title,
              const testing::Settings &settings,
              const std::string       &parameter_file,
              const unsigned int       b,
              const double             ratio,
              const unsigned int       k)
  {
    ParameterHandler prm;
    const Parameters parameters =
      testing::make_parameters(prm, settings, parameter_file);
    const auto  scene = scenes::create_scene(parameters, prm);
    auto        out   = testing::root_output();
    ElasticBody body(MPI_COMM_WORLD,
                     *scene,
                     b,
                     parameters.mesh.cell_type,
                     0,
                     parameters.finite_elements);
    body.setup_system();
    Vector<double> ratios(body.triangulation().n_active_cells());
    ratios                 = ratio;
    const auto       field = nodal_size_field(body, ratios);
    Triangulation<2> geometry;
    body.create_scene_coarse_mesh(geometry);
    const auto          &description = body.description();
    const CoarseMeshData unsplit =
      remesh_with_gmsh(geometry,
                       field,
                       body.name(),
                       MPI_COMM_WORLD,
                       RemeshingAlgorithm::frontal_delaunay,
                       description.interior_lines(),
                       description.support_points);
    CoarseMeshData mesh = unsplit;
    split_triangles(mesh, geometry, k);

    out << title << ", " << body.name() << ", k = " << k << ":" << std::endl;
    const unsigned int n_children = std::pow(4, k);
    const bool counted = mesh.cells.size() == n_children * unsplit.cells.size();
    out << "  " << n_children << " x " << unsplit.cells.size()
        << " cells: " << (counted ? "yes" : "no") << std::endl;

    const Conformity before = conformity(unsplit), after = conformity(mesh);
    Triangulation<2> tria;
    mesh.create_triangulation(tria);
    const bool conforming = after.conforming && before.conforming &&
                            after.euler == before.euler &&
                            tria.n_active_cells() == mesh.cells.size();
    out << "  conforming (" << mesh.boundary_lines.boundary_lines.size()
        << " boundary lines = the edges of one cell, V - E + F = "
        << after.euler << " as before): " << (conforming ? "yes" : "no")
        << std::endl;

    // Lengths and area: equal where straight; on curves, growing.
    bool curved        = false;
    bool lengths_agree = true;
    for (const auto &line : unsplit.boundary_lines.boundary_lines)
      curved = curved || line.manifold_id != numbers::flat_manifold_id;
    out << "  boundary lengths";
    for (const auto &[id, length] : before.lengths)
      {
        const double split_length = after.lengths.at(id);
        out << ", id " << int(id) << ": " << std::setprecision(8)
            << split_length;
        lengths_agree = lengths_agree &&
                        (curved ? split_length >= length * (1 - 1e-12) :
                                  std::abs(split_length / length - 1) < 1e-12);
      }
    const bool area_agrees = curved ?
                               after.area >= before.area * (1 - 1e-12) :
                               std::abs(after.area / before.area - 1) < 1e-12;
    out << (curved ? " (curved: not shorter than gmsh's): " :
                     " (gmsh's to 1e-12): ")
        << (lengths_agree ? "yes" : "no") << "; area " << std::setprecision(8)
        << after.area << ": " << (area_agrees ? "yes" : "no") << std::endl;

    double curve_distance = 0;
    if (curved)
      {
        curve_distance = distance_from_curves(mesh, geometry, unsplit);
        out << "  curved boundary vertices on their curves (circle 1e-9 "
               "relative, spline 1e-9 mm): "
            << (curve_distance < 1e-9 ? "yes" : "no") << std::endl;
      }

    // Angles: each child's smallest angle is its ancestor's, but next to a
    // curve.
    std::set<unsigned int> on_curve;
    for (const auto &line : unsplit.boundary_lines.boundary_lines)
      if (line.manifold_id != numbers::flat_manifold_id)
        on_curve.insert({line.vertices[0], line.vertices[1]});
    double largest_change = 0, smallest_before = numbers::PI,
           smallest_after = numbers::PI;
    for (std::size_t c = 0; c < mesh.cells.size(); ++c)
      {
        const CellData<2> &parent = unsplit.cells[c / n_children];
        const double       angle  = min_angle(mesh, mesh.cells[c]);
        smallest_after            = std::min(smallest_after, angle);
        if (std::none_of(parent.vertices.begin(),
                         parent.vertices.end(),
                         [&](const unsigned int v) {
                           return on_curve.count(v) > 0;
                         }))
          largest_change =
            std::max(largest_change,
                     std::abs(angle - min_angle(unsplit, parent)));
      }
    for (const auto &cell : unsplit.cells)
      smallest_before = std::min(smallest_before, min_angle(unsplit, cell));
    const bool angles_kept =
      largest_change < 1e-10 &&
      (curved || std::abs(smallest_after - smallest_before) < 1e-10);
    out << "  each cell's smallest angle its ancestor's"
        << (curved ? " (off curves)" : "") << ", smallest "
        << std::setprecision(4) << smallest_after * 180 / numbers::PI
        << " deg (gmsh's " << smallest_before * 180 / numbers::PI
        << "): " << (angles_kept ? "yes" : "no") << std::endl;

    // The interior lines' edges and the supports.
    bool features_kept = true;
    for (const auto &line : description.interior_lines())
      {
        const Tensor<1, 2> t       = line[1] - line[0];
        const double       length  = t.norm();
        const auto         on_line = [&](const Point<2> &x) {
          const Tensor<1, 2> d = x - line[0];
          return std::abs(d[0] * t[1] - d[1] * t[0]) < 1e-12 * length * length;
        };
        std::set<Edge> edges;
        for (const auto &cell : mesh.cells)
          for (unsigned int v = 0; v < 3; ++v)
            {
              const unsigned int a = cell.vertices[v],
                                 c = cell.vertices[(v + 1) % 3];
              if (on_line(mesh.vertices[a]) && on_line(mesh.vertices[c]))
                edges.insert(edge(a, c));
            }
        double covered = 0;
        for (const auto &[a, c] : edges)
          covered += mesh.vertices[a].distance(mesh.vertices[c]);
        features_kept = features_kept && std::abs(covered / length - 1) < 1e-12;
        out << "  interior line of " << length << " mm: edges of " << covered
            << " mm on it" << std::endl;
      }
    for (const auto &p : description.support_points)
      features_kept =
        features_kept &&
        std::any_of(mesh.vertices.begin(),
                    mesh.vertices.end(),
                    [&](const Point<2> &x) { return x.distance(p) < 1e-12; });
    if (!description.support_points.empty())
      out << "  " << description.support_points.size()
          << " point supports are vertices: " << (features_kept ? "yes" : "no")
          << std::endl;

    AssertThrow(counted && conforming && lengths_agree && area_agrees &&
                  curve_distance < 1e-9 && angles_kept && features_kept,
                ExcMessage("the split of " + title + ", " + body.name() +
                           " is wrong"));
  }



  // The quarter press fit, P1, remeshed once with the split: Lame's
  // pressure as tests/press_fit_adapted_p1 checks it.
  void
  check_press_fit_run()
  {
    auto                    out = testing::root_output();
    const testing::PressFit press_fit;
    const double            p = press_fit.pressure();
    testing::ProgramRun     run(
      {{"Scene/Gmsh/Mesh file",
            testing::example_file("meshes/press_fit_quarter.geo")},
           {"Finite elements/Polynomial degree", "1"},
           {"Adaptation/Strategy", "remesh"},
           {"Adaptation/Target error", "0.5"},
           {"Adaptation/Number of cycles", "2"},
           {"Adaptation/Remeshing split above cells", "1000"},
           {"Output/Write VTU", "false"},
           {"Output/Output directory", "remesh_triangle_split_press_fit"}},
      testing::example_file("press_fit_quarter.prm"));
    const auto &cycles = run.summary["cycles"];
    AssertThrow(cycles.size() == 2,
                ExcMessage("the remeshed cycle did not run: " +
                           run.summary["stop_reason"].get<std::string>()));
    const auto &cycle = cycles[1];
    const auto  splits =
      cycle["adaptation"]["triangle_splits"].get<std::vector<unsigned int>>();
    const double overlap = cycle["initial_overlap"].get<double>();
    const testing::SlavePressures pressures =
      testing::read_slave_pressures(run.parameters.output.directory, 1, p);
    const unsigned int active = cycle["active_nodes"].get<unsigned int>();
    out << "press fit, P1, remeshed, split k = " << splits[0] << ", "
        << splits[1] << ": " << cycle["n_dofs"].get<unsigned long>()
        << " DoFs, " << active << " of " << pressures.n_nodes
        << " slave nodes in contact, overlap / delta - 1 "
        << (std::abs(overlap / press_fit.delta - 1) < 1e-9 ? "below 1e-9" :
                                                             "ABOVE 1e-9")
        << ", largest deviation from p " << std::setprecision(3)
        << 100 * pressures.largest_deviation << " % (within 1 %: "
        << (pressures.largest_deviation < 0.01 ? "yes" : "no") << ")"
        << std::endl;
    AssertThrow(splits[0] + splits[1] > 0 &&
                  std::abs(overlap / press_fit.delta - 1) < 1e-9 &&
                  active == pressures.n_nodes && pressures.n_nodes > 0 &&
                  pressures.largest_deviation < 0.01,
                ExcMessage("split press fit: overlap " +
                           std::to_string(overlap) + ", deviation " +
                           std::to_string(pressures.largest_deviation)));
  }



  // blocks remeshed with the split: the contact force on the upper block
  // (the slave, from the contact CSV) balances its load.
  void
  check_blocks_run()
  {
    auto                out = testing::root_output();
    testing::ProgramRun run({{"Adaptation/Target error", "2"},
                             {"Adaptation/Number of cycles", "3"},
                             {"Adaptation/Remeshing split above cells", "300"},
                             {"Output/Write VTU", "false"},
                             {"Output/Output directory",
                              "remesh_triangle_split_blocks"}},
                            testing::example_file("blocks.prm"));
    const auto         &cycles = run.summary["cycles"];
    const double        load   = 100 * 10; // N/mm on the upper block's top
    for (const auto &cycle : cycles)
      {
        const unsigned int c = cycle["cycle"].get<unsigned int>();
        if (c == 0)
          continue;
        const auto splits = cycle["adaptation"]["triangle_splits"]
                              .get<std::vector<unsigned int>>();
        std::ifstream file(run.parameters.output.directory + "/contact_00" +
                           std::to_string(c) + ".csv");
        std::string   line;
        std::getline(file, line);
        double normal = 0, tangential = 0;
        while (std::getline(file, line))
          {
            std::stringstream        row(line);
            std::string              value;
            std::vector<std::string> values;
            while (std::getline(row, value, ','))
              values.push_back(value);
            normal += std::stod(values[4]) * std::stod(values[5]);
            tangential += std::stod(values[4]) * std::stod(values[6]);
          }
        const bool balanced = std::abs(normal / load - 1) < 1e-10 &&
                              std::abs(tangential / load) < 1e-10;
        out << "blocks, cycle " << c << ", split k = " << splits[0] << ", "
            << splits[1] << ": " << cycle["n_dofs"].get<unsigned long>()
            << " DoFs, eps " << std::fixed << std::setprecision(3)
            << 100 * cycle["epsilon"].get<double>() << std::defaultfloat
            << " %, contact force = load to 1e-10: "
            << (balanced ? "yes" : "no") << std::endl;
        AssertThrow(splits[0] + splits[1] > 0 && balanced,
                    ExcMessage("split blocks, cycle " + std::to_string(c) +
                               ": contact force " + std::to_string(normal) +
                               ", " + std::to_string(tangential)));
      }
    AssertThrow(cycles.size() >= 2,
                ExcMessage("no remeshed cycle ran: " +
                           run.summary["stop_reason"].get<std::string>()));
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  check_split("blocks (centre line held)",
              {{"Scene/Name", "blocks"},
               {"Mesh/Cell type", "triangle"},
               {"Scene/Blocks/Hold centre line", "true"}},
              "",
              0,
              0.5,
              2);
  check_split("blocks", {}, testing::example_file("blocks.prm"), 1, 0.5, 1);
  for (unsigned int b = 0; b < 2; ++b)
    check_split("quarter press fit (circles)",
                {{"Scene/Gmsh/Mesh file",
                  testing::example_file("meshes/press_fit_quarter.geo")}},
                testing::example_file("press_fit_quarter.prm"),
                b,
                1,
                2);
  check_split("quarter press fit (splines)",
              {{"Scene/Gmsh/Mesh file",
                std::string(COULOMB_ADAPT_TEST_DATA_DIR) +
                  "/press_fit_quarter_splines.geo"}},
              testing::example_file("press_fit_quarter.prm"),
              0,
              1,
              2);
  check_split("press fit (point supports)",
              {{"Scene/Gmsh/Mesh file",
                testing::example_file("meshes/press_fit.geo")}},
              testing::example_file("press_fit.prm"),
              1,
              1,
              1);
  check_press_fit_run();
  check_blocks_run();
}
