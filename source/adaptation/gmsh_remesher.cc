#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/adaptation/gmsh_remesher.h>

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace coulomb_adapt
{
  std::vector<SizeFieldTriangle>
  nodal_size_field(const ElasticBody &body, const Vector<double> &ratio)
  {
    // Per owned cell, packed for the gather: three vertices, h*_E, |E|.
    constexpr unsigned int n_values = 8;
    std::vector<double>    local;
    for (const auto &cell : body.triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          AssertThrow(cell->n_vertices() == 3,
                      ExcMessage("the size field is built on triangles"));
          for (unsigned int v = 0; v < 3; ++v)
            {
              local.push_back(cell->vertex(v)[0]);
              local.push_back(cell->vertex(v)[1]);
            }
          const double h = std::sqrt(4 * cell->measure() / std::sqrt(3.));
          local.push_back(ratio(cell->active_cell_index()) * h);
          local.push_back(cell->measure());
        }
    // Only rank 0 meshes. The cells are put in a fixed order, whatever the
    // partition: gmsh's result depends on the order of the view's
    // triangles and on the last bits of the sizes, and the mesh must not
    // depend on the number of ranks. The sizes are rounded to float for the
    // same reason (r_E comes from MPI sums).
    const auto gathered =
      Utilities::MPI::gather(body.dof_handler().get_communicator(), local, 0);
    std::vector<std::array<double, n_values>> cells;
    for (const auto &part : gathered)
      for (std::size_t c = 0; c < part.size(); c += n_values)
        {
          std::array<double, n_values> cell;
          std::copy(part.begin() + c,
                    part.begin() + c + n_values,
                    cell.begin());
          cell[6] = static_cast<float>(cell[6]);
          cells.push_back(cell);
        }
    std::sort(cells.begin(), cells.end());

    // Geometric mean at the vertices: sizes vary over orders of magnitude.
    std::map<std::pair<double, double>, std::pair<double, unsigned int>>
      log_sum;
    for (const auto &cell : cells)
      for (unsigned int v = 0; v < 3; ++v)
        {
          auto &entry = log_sum[{cell[2 * v], cell[2 * v + 1]}];
          entry.first += std::log(cell[6]);
          ++entry.second;
        }

    // Smoothing must not change the cell count the optimum asked for: the
    // count of a size field is int 1 / (sqrt 3 / 4 h(x)^2) dx, with h
    // constant per cell before and linear per cell after the smoothing
    // (integrated at the edge midpoints). Near a singular point the
    // smoothed field is much finer on average, so without this scaling the
    // new mesh has up to a third more cells than N*.
    std::vector<SizeFieldTriangle> field(cells.size());
    double                         n_wanted = 0, n_smoothed = 0;
    for (std::size_t c = 0; c < cells.size(); ++c)
      {
        const double area = cells[c][7];
        for (unsigned int v = 0; v < 3; ++v)
          {
            const auto &entry = log_sum[{cells[c][2 * v], cells[c][2 * v + 1]}];
            field[c].vertices[v] =
              Point<2>(cells[c][2 * v], cells[c][2 * v + 1]);
            field[c].size[v] = std::exp(entry.first / entry.second);
          }
        n_wanted += area / (cells[c][6] * cells[c][6]);
        for (unsigned int v = 0; v < 3; ++v)
          {
            const double h =
              0.5 * (field[c].size[v] + field[c].size[(v + 1) % 3]);
            n_smoothed += area / 3 / (h * h);
          }
      }
    const double scale = n_wanted > 0 ? std::sqrt(n_smoothed / n_wanted) : 1;
    for (auto &t : field)
      for (double &h : t.size)
        h = static_cast<float>(h * scale);
    return field;
  }



  namespace
  {
    struct BoundaryFace
    {
      unsigned int       a, b;
      types::boundary_id boundary_id;
      types::manifold_id manifold_id;
    };

    // The boundary faces of @p tria as closed chains (the outer boundary
    // and one per hole), each face oriented along its chain's walk.
    std::vector<std::vector<BoundaryFace>>
    boundary_loops(const Triangulation<2> &tria, const std::string &body_name)
    {
      std::vector<BoundaryFace> faces;
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            faces.push_back({face->vertex_index(0),
                             face->vertex_index(1),
                             face->boundary_id(),
                             face->manifold_id()});
      std::multimap<unsigned int, unsigned int> at_vertex;
      for (unsigned int f = 0; f < faces.size(); ++f)
        {
          at_vertex.emplace(faces[f].a, f);
          at_vertex.emplace(faces[f].b, f);
        }
      std::vector<bool>                      used(faces.size(), false);
      std::vector<std::vector<BoundaryFace>> loops;
      for (unsigned int first = 0; first < faces.size(); ++first)
        {
          if (used[first])
            continue;
          std::vector<BoundaryFace> loop = {faces[first]};
          used[first]                    = true;
          while (loop.back().b != loop.front().a)
            {
              const unsigned int v     = loop.back().b;
              bool               found = false;
              for (auto [it, end] = at_vertex.equal_range(v); it != end; ++it)
                if (!used[it->second])
                  {
                    BoundaryFace next = faces[it->second];
                    if (next.a != v)
                      std::swap(next.a, next.b);
                    used[it->second] = true;
                    loop.push_back(next);
                    found = true;
                    break;
                  }
              AssertThrow(found,
                          ExcMessage("remeshing " + body_name +
                                     ": its boundary is not made of closed "
                                     "curves"));
            }
          loops.push_back(loop);
        }
      return loops;
    }



    // One gmsh curve: a run of boundary vertices.
    struct Curve
    {
      std::vector<unsigned int> vertices;
      types::boundary_id        boundary_id;
      types::manifold_id        manifold_id;
    };

    // @p corners: vertices where a curve must end even inside a straight
    // run or an arc (end points of interior lines).
    std::vector<Curve>
    boundary_curves(const Triangulation<2>          &tria,
                    const std::vector<BoundaryFace> &loop,
                    const std::set<unsigned int>    &corners)
    {
      const auto &vertices  = tria.get_vertices();
      auto        direction = [&](const BoundaryFace &f) {
        const Tensor<1, 2> d = vertices[f.b] - vertices[f.a];
        return d / d.norm();
      };
      // A curve ends where the boundary data change, or where a straight
      // run turns.
      auto breaks_between = [&](const BoundaryFace &f, const BoundaryFace &g) {
        if (f.boundary_id != g.boundary_id || f.manifold_id != g.manifold_id ||
            corners.count(g.a) > 0)
          return true;
        if (f.manifold_id != numbers::flat_manifold_id)
          return false;
        const Tensor<1, 2> s = direction(f), t = direction(g);
        return std::abs(s[0] * t[1] - s[1] * t[0]) > 1e-10 || s * t < 0;
      };
      const unsigned int n     = loop.size();
      unsigned int       start = 0;
      while (start < n &&
             !breaks_between(loop[(start + n - 1) % n], loop[start]))
        ++start;
      if (start == n) // a closed smooth curve: any vertex will do
        start = 0;

      std::vector<Curve> curves;
      for (unsigned int k = 0; k < n; ++k)
        {
          const BoundaryFace &f = loop[(start + k) % n];
          if (k == 0 || breaks_between(loop[(start + k + n - 1) % n], f))
            curves.push_back({{f.a}, f.boundary_id, f.manifold_id});
          curves.back().vertices.push_back(f.b);
        }
      return curves;
    }



    double
    angle_between(const Point<2> &centre, const Point<2> &p, const Point<2> &q)
    {
      const Tensor<1, 2> u = p - centre, v = q - centre;
      return std::abs(std::atan2(u[0] * v[1] - u[1] * v[0], u * v));
    }



    // Mesh in gmsh; the elements and the boundary lines of each curve.
    CoarseMeshData
    mesh_in_gmsh(const Triangulation<2>                     &geometry,
                 const std::vector<SizeFieldTriangle>       &size_field,
                 const std::string                          &body_name,
                 const int                                   algorithm,
                 const std::vector<std::array<Point<2>, 2>> &interior_lines,
                 const std::vector<Point<2>>                &support_points)
    {
      const auto &vertices = geometry.get_vertices();
      // The boundary vertices at the interior lines' ends.
      const double tolerance = 1e-10 * GridTools::diameter(geometry);
      const auto   boundary_vertices =
        GridTools::get_all_vertices_at_boundary(geometry);
      std::vector<std::array<unsigned int, 2>> line_ends;
      std::set<unsigned int>                   corners;
      for (const auto &line : interior_lines)
        {
          std::array<unsigned int, 2> ends;
          for (unsigned int e = 0; e < 2; ++e)
            {
              ends[e] =
                GridTools::find_closest_vertex(boundary_vertices, line[e]);
              AssertThrow(vertices[ends[e]].distance(line[e]) < tolerance,
                          ExcMessage("remeshing " + body_name +
                                     ": the end of an interior line (a "
                                     "symmetry line) is not a vertex of the "
                                     "boundary"));
              corners.insert(ends[e]);
            }
          line_ends.push_back(ends);
        }
      // Point supports: on the boundary a curve ends there, inside the
      // body the point is embedded; either way it stays a node.
      std::vector<Point<2>> embedded_points;
      for (const auto &p : support_points)
        {
          const unsigned int v =
            GridTools::find_closest_vertex(boundary_vertices, p);
          if (vertices[v].distance(p) < tolerance)
            corners.insert(v);
          else
            embedded_points.push_back(p);
        }
      // The curves of each boundary loop; the outer boundary is the loop
      // of the largest area, the others are holes.
      const auto                loops = boundary_loops(geometry, body_name);
      std::vector<Curve>        curves;
      std::vector<unsigned int> first_curve_of_loop;
      unsigned int              outer        = 0;
      double                    largest_area = -1;
      for (unsigned int l = 0; l < loops.size(); ++l)
        {
          double area = 0;
          for (const auto &f : loops[l])
            area += vertices[f.a][0] * vertices[f.b][1] -
                    vertices[f.b][0] * vertices[f.a][1];
          if (std::abs(area) > largest_area)
            {
              largest_area = std::abs(area);
              outer        = l;
            }
          first_curve_of_loop.push_back(curves.size());
          const auto loop_curves = boundary_curves(geometry, loops[l], corners);
          curves.insert(curves.end(), loop_curves.begin(), loop_curves.end());
        }
      first_curve_of_loop.push_back(curves.size());

      gmsh::model::add(body_name);
      std::map<unsigned int, int> point_tag;
      auto                        point = [&](const unsigned int v) {
        auto it = point_tag.find(v);
        if (it == point_tag.end())
          it = point_tag
                 .emplace(v,
                          gmsh::model::geo::addPoint(vertices[v][0],
                                                     vertices[v][1],
                                                     0))
                 .first;
        return it->second;
      };
      std::vector<std::vector<int>> loop_tags(loops.size());
      std::map<int, unsigned int>   curve_index; // gmsh curve -> curves[]
      for (unsigned int c = 0; c < curves.size(); ++c)
        {
          const unsigned int loop_of_curve =
            std::upper_bound(first_curve_of_loop.begin(),
                             first_curve_of_loop.end(),
                             c) -
            first_curve_of_loop.begin() - 1;
          const Curve     &curve = curves[c];
          std::vector<int> tags;
          if (curve.manifold_id == numbers::flat_manifold_id)
            tags.push_back(
              gmsh::model::geo::addLine(point(curve.vertices.front()),
                                        point(curve.vertices.back())));
          else
            {
              const auto *sphere = dynamic_cast<const SphericalManifold<2> *>(
                &geometry.get_manifold(curve.manifold_id));
              AssertThrow(sphere != nullptr,
                          ExcMessage("remeshing " + body_name +
                                     ": a curved boundary that is not a "
                                     "circle (SphericalManifold) is not "
                                     "supported"));
              const Point<2> centre = sphere->center;
              const int      centre_tag =
                gmsh::model::geo::addPoint(centre[0], centre[1], 0);
              // gmsh's arcs must be shorter than pi: split at coarse
              // vertices into arcs of at most a quarter circle.
              std::size_t first = 0;
              while (first + 1 < curve.vertices.size())
                {
                  std::size_t last = first + 1;
                  while (last + 1 < curve.vertices.size() &&
                         angle_between(centre,
                                       vertices[curve.vertices[first]],
                                       vertices[curve.vertices[last + 1]]) <=
                           numbers::PI / 2 + 1e-12)
                    ++last;
                  tags.push_back(gmsh::model::geo::addCircleArc(
                    point(curve.vertices[first]),
                    centre_tag,
                    point(curve.vertices[last])));
                  first = last;
                }
            }
          for (const int t : tags)
            {
              loop_tags[loop_of_curve].push_back(t);
              curve_index[t] = c;
            }
        }
      std::vector<int> loop_list = {
        gmsh::model::geo::addCurveLoop(loop_tags[outer])};
      for (unsigned int l = 0; l < loops.size(); ++l)
        if (l != outer)
          loop_list.push_back(gmsh::model::geo::addCurveLoop(loop_tags[l]));
      const int        surface = gmsh::model::geo::addPlaneSurface(loop_list);
      std::vector<int> point_tags;
      for (const auto &p : embedded_points)
        point_tags.push_back(gmsh::model::geo::addPoint(p[0], p[1], 0));
      std::vector<int> interior_tags;
      for (const auto &ends : line_ends)
        interior_tags.push_back(
          gmsh::model::geo::addLine(point(ends[0]), point(ends[1])));
      gmsh::model::geo::synchronize();
      if (!interior_tags.empty())
        gmsh::model::mesh::embed(1, interior_tags, 2, surface);
      if (!point_tags.empty())
        gmsh::model::mesh::embed(0, point_tags, 2, surface);

      // The size field: a list-based view of triangles with nodal sizes.
      const int           view = gmsh::view::add("size field");
      std::vector<double> data;
      double              h_min = std::numeric_limits<double>::max(), h_max = 0;
      for (const auto &t : size_field)
        {
          for (unsigned int d = 0; d < 2; ++d)
            for (unsigned int v = 0; v < 3; ++v)
              data.push_back(t.vertices[v][d]);
          for (unsigned int v = 0; v < 3; ++v)
            data.push_back(0.);
          for (unsigned int v = 0; v < 3; ++v)
            {
              data.push_back(t.size[v]);
              h_min = std::min(h_min, t.size[v]);
              h_max = std::max(h_max, t.size[v]);
            }
        }
      gmsh::view::addListData(view, "ST", size_field.size(), data);
      const int field = gmsh::model::mesh::field::add("PostView");
      gmsh::model::mesh::field::setNumber(field, "ViewTag", view);
      gmsh::model::mesh::field::setAsBackgroundMesh(field);
      gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
      gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
      gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
      // Outside the view (curved boundaries bulge out of the old polygon)
      // gmsh's PostView gives a huge size: keep to the field's range.
      gmsh::option::setNumber("Mesh.MeshSizeMin", h_min);
      gmsh::option::setNumber("Mesh.MeshSizeMax", h_max);
      gmsh::option::setNumber("Mesh.Algorithm", algorithm);
      gmsh::model::mesh::generate(2);

      std::vector<std::size_t> node_tags;
      std::vector<double>      coordinates, parametric;
      gmsh::model::mesh::getNodes(
        node_tags, coordinates, parametric, -1, -1, true, false);
      // The mesh as CoarseMeshData: what build_body_mesh
      // (scenes/gmsh_reader.h) makes of gmsh's elements, with the same
      // vertex, cell and line order, so the same mesh, but on flat arrays
      // instead of maps and one vector per element, and without its check
      // that each line is a boundary edge (the lines here are those of the
      // boundary curves gmsh meshed): on large meshes that check and the
      // maps were a large part of the remeshing time
      // (benchmarks/adaptive_run).
      std::size_t max_tag = 0;
      for (const std::size_t t : node_tags)
        max_tag = std::max(max_tag, t);
      std::vector<std::size_t> node_of_tag(max_tag + 1);
      for (std::size_t i = 0; i < node_tags.size(); ++i)
        node_of_tag[node_tags[i]] = i;
      constexpr unsigned int    invalid = numbers::invalid_unsigned_int;
      std::vector<unsigned int> local_index(max_tag + 1, invalid);

      CoarseMeshData mesh;
      auto           vertex = [&](const std::size_t tag) {
        if (local_index[tag] == invalid)
          {
            local_index[tag]    = mesh.vertices.size();
            const std::size_t i = node_of_tag[tag];
            mesh.vertices.emplace_back(coordinates[3 * i],
                                       coordinates[3 * i + 1]);
          }
        return local_index[tag];
      };
      const types::material_id material_id =
        geometry.begin_active()->material_id();
      {
        std::vector<int>                      types;
        std::vector<std::vector<std::size_t>> element_tags, element_nodes;
        gmsh::model::mesh::getElements(
          types, element_tags, element_nodes, 2, surface);
        for (unsigned int t = 0; t < types.size(); ++t)
          for (std::size_t e = 0; e < element_tags[t].size(); ++e)
            {
              CellData<2> cell(3);
              for (unsigned int v = 0; v < 3; ++v)
                cell.vertices[v] = vertex(element_nodes[t][3 * e + v]);
              // deal.II wants counter-clockwise triangles (the shoelace
              // formula, as build_body_mesh evaluates it).
              double area = 0;
              for (unsigned int v = 0; v < 3; ++v)
                {
                  const Point<2> &p = mesh.vertices[cell.vertices[v]];
                  const Point<2> &q = mesh.vertices[cell.vertices[(v + 1) % 3]];
                  area += p[0] * q[1] - q[0] * p[1];
                }
              if (0.5 * area < 0)
                std::swap(cell.vertices[1], cell.vertices[2]);
              cell.material_id = material_id;
              mesh.cells.push_back(cell);
            }
      }
      // Lines by curve index (the boundary id until renamed below), each
      // curve's in gmsh's order.
      std::map<unsigned int, std::vector<int>> tags_of_curve;
      for (const auto &[tag, c] : curve_index)
        tags_of_curve[c].push_back(tag);
      for (const auto &[c, tags] : tags_of_curve)
        for (const int tag : tags)
          {
            std::vector<int>                      types;
            std::vector<std::vector<std::size_t>> element_tags, element_nodes;
            gmsh::model::mesh::getElements(
              types, element_tags, element_nodes, 1, tag);
            for (unsigned int t = 0; t < types.size(); ++t)
              for (std::size_t e = 0; e < element_tags[t].size(); ++e)
                {
                  const auto edge =
                    std::minmax(local_index[element_nodes[t][2 * e]],
                                local_index[element_nodes[t][2 * e + 1]]);
                  AssertThrow(edge.first != invalid && edge.second != invalid,
                              ExcMessage("remeshing " + body_name +
                                         ": a boundary node of gmsh's mesh "
                                         "is not a vertex of a triangle"));
                  CellData<1> line;
                  line.vertices    = {edge.first, edge.second};
                  line.boundary_id = c;
                  mesh.boundary_lines.boundary_lines.push_back(line);
                }
          }
      for (auto &line : mesh.boundary_lines.boundary_lines)
        {
          const Curve &curve = curves[line.boundary_id];
          line.boundary_id   = curve.boundary_id;
          line.manifold_id   = curve.manifold_id;
        }
      return mesh;
    }



    // CoarseMeshData as numbers, for the broadcast.
    std::vector<double>
    pack(const CoarseMeshData &mesh)
    {
      std::vector<double> data = {double(mesh.vertices.size()),
                                  double(mesh.cells.size()),
                                  double(
                                    mesh.boundary_lines.boundary_lines.size())};
      for (const auto &v : mesh.vertices)
        data.insert(data.end(), {v[0], v[1]});
      for (const auto &c : mesh.cells)
        data.insert(data.end(),
                    {double(c.vertices[0]),
                     double(c.vertices[1]),
                     double(c.vertices[2]),
                     double(c.material_id)});
      for (const auto &l : mesh.boundary_lines.boundary_lines)
        data.insert(data.end(),
                    {double(l.vertices[0]),
                     double(l.vertices[1]),
                     double(l.boundary_id),
                     double(l.manifold_id)});
      return data;
    }

    CoarseMeshData
    unpack(const std::vector<double> &data)
    {
      CoarseMeshData mesh;
      std::size_t    k       = 3;
      const auto     n_lines = static_cast<std::size_t>(data[2]);
      for (std::size_t i = 0; i < static_cast<std::size_t>(data[0]);
           ++i, k += 2)
        mesh.vertices.emplace_back(data[k], data[k + 1]);
      for (std::size_t i = 0; i < static_cast<std::size_t>(data[1]);
           ++i, k += 4)
        {
          CellData<2> cell(3);
          for (unsigned int v = 0; v < 3; ++v)
            cell.vertices[v] = static_cast<unsigned int>(data[k + v]);
          cell.material_id = static_cast<types::material_id>(data[k + 3]);
          mesh.cells.push_back(cell);
        }
      for (std::size_t i = 0; i < n_lines; ++i, k += 4)
        {
          CellData<1> line;
          line.vertices    = {static_cast<unsigned int>(data[k]),
                              static_cast<unsigned int>(data[k + 1])};
          line.boundary_id = static_cast<types::boundary_id>(data[k + 2]);
          line.manifold_id = static_cast<types::manifold_id>(data[k + 3]);
          mesh.boundary_lines.boundary_lines.push_back(line);
        }
      return mesh;
    }
  } // namespace



  CoarseMeshData
  remesh_with_gmsh(const Triangulation<2>                     &geometry,
                   const std::vector<SizeFieldTriangle>       &size_field,
                   const std::string                          &body_name,
                   const MPI_Comm                              comm,
                   const std::string                          &algorithm,
                   const std::vector<std::array<Point<2>, 2>> &interior_lines,
                   const std::vector<Point<2>>                &support_points)
  {
    // gmsh's Mesh.Algorithm numbers.
    const int algorithm_number = algorithm == "delaunay" ? 5 : 6;
    // One rank meshes (gmsh is serial), every rank gets the mesh.
    std::vector<double> data;
    std::string         error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 0);
        try
          {
            data = pack(mesh_in_gmsh(geometry,
                                     size_field,
                                     body_name,
                                     algorithm_number,
                                     interior_lines,
                                     support_points));
          }
        catch (const std::exception &e)
          {
            error = e.what();
          }
        catch (const std::string &thrown)
          {
            error = "gmsh: " + gmsh_error_message(thrown);
          }
        catch (...)
          {
            error = "gmsh: " + gmsh_error_message("");
          }
        gmsh::finalize();
      }
    error = Utilities::MPI::broadcast(comm, error, 0);
    AssertThrow(error.empty(),
                ExcMessage("remeshing " + body_name + " failed: " + error));
    return unpack(Utilities::MPI::broadcast(comm, data, 0));
  }
} // namespace coulomb_adapt
