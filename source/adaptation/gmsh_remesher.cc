#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <coulomb_adapt/adaptation/boundary_curves.h>
#include <coulomb_adapt/adaptation/gmsh_remesher.h>
#include <coulomb_adapt/adaptation/triangle_split.h>
#include <coulomb_adapt/scenes/curve_manifold.h>

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace coulomb_adapt
{
  namespace
  {
    using namespace boundary_geometry;



    double
    angle_between(const Point<2> &centre, const Point<2> &p, const Point<2> &q)
    {
      const Tensor<1, 2> u = p - centre, v = q - centre;
      return std::abs(std::atan2(u[0] * v[1] - u[1] * v[0], u * v));
    }



    // gmsh's geometry points at vertices of the old mesh, each added once
    // (a vertex ends two curves).
    class GmshPoints
    {
    public:
      explicit GmshPoints(const std::vector<Point<2>> &vertices)
        : vertices(vertices)
      {}

      int
      operator()(const unsigned int v)
      {
        auto it = tag.find(v);
        if (it == tag.end())
          it = tag
                 .emplace(v,
                          gmsh::model::geo::addPoint(vertices[v][0],
                                                     vertices[v][1],
                                                     0))
                 .first;
        return it->second;
      }

    private:
      const std::vector<Point<2>> &vertices;
      std::map<unsigned int, int>  tag;
    };



    // A curve on a circle (SphericalManifold) as gmsh circle arcs. gmsh's
    // arcs must be shorter than pi: split at coarse vertices into arcs of
    // at most a quarter circle.
    std::vector<int>
    add_circle_arcs(const Triangulation<2>     &geometry,
                    const Curve                &curve,
                    const SphericalManifold<2> &sphere,
                    GmshPoints                 &point)
    {
      const auto    &vertices = geometry.get_vertices();
      const Point<2> centre   = sphere.center;
      const int      centre_tag =
        gmsh::model::geo::addPoint(centre[0], centre[1], 0);
      std::vector<int> tags;
      std::size_t      first = 0;
      while (first + 1 < curve.vertices.size())
        {
          std::size_t last = first + 1;
          while (last + 1 < curve.vertices.size() &&
                 angle_between(centre,
                               vertices[curve.vertices[first]],
                               vertices[curve.vertices[last + 1]]) <=
                   numbers::PI / 2 + 1e-12)
            ++last;
          tags.push_back(
            gmsh::model::geo::addCircleArc(point(curve.vertices[first]),
                                           centre_tag,
                                           point(curve.vertices[last])));
          first = last;
        }
      return tags;
    }



    // A curve on a sampled curve of the scene (CurveManifold: a spline of
    // its .geo) as gmsh splines through points of that curve, from the
    // run's first vertex to its last at the manifold's sample spacing (8
    // to 1024 intervals). A run around a whole closed curve is split at
    // its middle vertex: a gmsh spline needs two distinct ends. gmsh's
    // spline (Catmull-Rom) is within a fraction of the spacing squared of
    // the curve; put_nodes_on_curves() then moves the nodes gmsh puts on
    // it onto the curve itself.
    std::vector<int>
    add_curve_splines(const Triangulation<2> &geometry,
                      const Curve            &curve,
                      const CurveManifold    &manifold,
                      GmshPoints             &point)
    {
      const auto &vertices = geometry.get_vertices();
      // The run's arc lengths, continued across the start of a closed
      // curve.
      std::vector<double> s;
      for (const unsigned int v : curve.vertices)
        {
          double next = manifold.pull_back(vertices[v])[0];
          if (!s.empty() && manifold.is_closed())
            next += manifold.length() *
                    std::round((s.back() - next) / manifold.length());
          s.push_back(next);
        }
      const std::size_t        n    = curve.vertices.size();
      std::vector<std::size_t> ends = {0, n - 1};
      if (curve.vertices.front() == curve.vertices.back())
        ends = {0, (n - 1) / 2, n - 1};
      const double     spacing = manifold.length() / manifold.n_intervals();
      std::vector<int> tags;
      for (std::size_t k = 0; k + 1 < ends.size(); ++k)
        {
          const double       s_a = s[ends[k]], s_b = s[ends[k + 1]];
          const unsigned int n_steps =
            std::clamp<unsigned int>(std::ceil(std::abs(s_b - s_a) / spacing),
                                     8,
                                     1024);
          std::vector<int> points = {point(curve.vertices[ends[k]])};
          for (unsigned int j = 1; j < n_steps; ++j)
            {
              const Point<2> x = manifold.push_forward(
                Point<1>(s_a + (s_b - s_a) * j / n_steps));
              points.push_back(gmsh::model::geo::addPoint(x[0], x[1], 0));
            }
          points.push_back(point(curve.vertices[ends[k + 1]]));
          tags.push_back(gmsh::model::geo::addSpline(points));
        }
      return tags;
    }



    // A curved run of boundary faces as gmsh curves, by its manifold.
    std::vector<int>
    add_curved(const Triangulation<2> &geometry,
               const Curve            &curve,
               const std::string      &body_name,
               GmshPoints             &point)
    {
      const Manifold<2> &manifold = geometry.get_manifold(curve.manifold_id);
      if (const auto *sphere =
            dynamic_cast<const SphericalManifold<2> *>(&manifold))
        return add_circle_arcs(geometry, curve, *sphere, point);
      if (const auto *sampled = dynamic_cast<const CurveManifold *>(&manifold))
        return add_curve_splines(geometry, curve, *sampled, point);
      AssertThrow(false,
                  ExcMessage("remeshing " + body_name +
                             ": a curved boundary that is neither a circle "
                             "(SphericalManifold) nor a sampled curve of the "
                             "scene (CurveManifold) is not supported"));
      return {};
    }



    // The body's geometry in gmsh: one plane surface per connected part,
    // bounded by the part's loops, with the interior lines and points
    // embedded in the part that holds them.
    struct GmshGeometry
    {
      std::vector<int>            surfaces;
      std::map<int, unsigned int> curve_index; // gmsh curve -> curves[]
    };

    GmshGeometry
    add_geometry(const Triangulation<2> &geometry,
                 const LoopCurves       &boundary,
                 const InteriorFeatures &features,
                 const std::string      &body_name)
    {
      gmsh::model::add(body_name);
      GmshPoints                    point(geometry.get_vertices());
      GmshGeometry                  result;
      std::vector<std::vector<int>> loop_tags(boundary.n_loops());
      for (unsigned int c = 0; c < boundary.curves.size(); ++c)
        {
          const Curve     &curve = boundary.curves[c];
          std::vector<int> tags;
          if (curve.manifold_id == numbers::flat_manifold_id)
            tags.push_back(
              gmsh::model::geo::addLine(point(curve.vertices.front()),
                                        point(curve.vertices.back())));
          else
            tags = add_curved(geometry, curve, body_name, point);
          for (const int t : tags)
            {
              loop_tags[boundary.loop_of_curve(c)].push_back(t);
              result.curve_index[t] = c;
            }
        }
      for (const auto &part : boundary.parts)
        {
          std::vector<int> loop_list;
          for (const unsigned int l : part)
            loop_list.push_back(gmsh::model::geo::addCurveLoop(loop_tags[l]));
          result.surfaces.push_back(
            gmsh::model::geo::addPlaneSurface(loop_list));
        }
      // Each embedded point and interior line goes to the surface of the
      // part that holds it (a line's midpoint: its ends are on the
      // boundary).
      const auto surface_of = [&](const Point<2> &x) {
        const unsigned int part = boundary.part_containing(x);
        AssertThrow(part != numbers::invalid_unsigned_int,
                    ExcMessage("remeshing " + body_name +
                               ": a point support or symmetry line at (" +
                               std::to_string(x[0]) + ", " +
                               std::to_string(x[1]) +
                               ") lies outside the body"));
        return result.surfaces[part];
      };
      std::map<int, std::vector<int>> point_tags, interior_tags;
      for (const auto &p : features.embedded_points)
        point_tags[surface_of(p)].push_back(
          gmsh::model::geo::addPoint(p[0], p[1], 0));
      const auto &vertices = geometry.get_vertices();
      for (const auto &ends : features.line_ends)
        interior_tags[surface_of(0.5 * (vertices[ends[0]] + vertices[ends[1]]))]
          .push_back(gmsh::model::geo::addLine(point(ends[0]), point(ends[1])));
      gmsh::model::geo::synchronize();
      for (const auto &[surface, tags] : interior_tags)
        gmsh::model::mesh::embed(1, tags, 2, surface);
      for (const auto &[surface, tags] : point_tags)
        gmsh::model::mesh::embed(0, tags, 2, surface);
      return result;
    }



    // The size field as gmsh's background mesh: a list-based view of
    // triangles with nodal sizes.
    void
    set_background_size_field(const std::vector<SizeFieldTriangle> &size_field)
    {
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
    }



    // gmsh's mesh as CoarseMeshData: what build_body_mesh
    // (scenes/gmsh_reader.h) makes of gmsh's elements, with the same
    // vertex, cell and line order, so the same mesh, but on flat arrays
    // instead of maps and one vector per element, and without its check
    // that each line is a boundary edge (the lines here are those of the
    // boundary curves gmsh meshed): on large meshes that check and the
    // maps were a large part of the remeshing time
    // (benchmarks/adaptive_run).
    class MeshFromGmsh
    {
    public:
      MeshFromGmsh()
      {
        std::vector<double> parametric;
        gmsh::model::mesh::getNodes(
          node_tags, coordinates, parametric, -1, -1, true, false);
        std::size_t max_tag = 0;
        for (const std::size_t t : node_tags)
          max_tag = std::max(max_tag, t);
        node_of_tag.resize(max_tag + 1);
        for (std::size_t i = 0; i < node_tags.size(); ++i)
          node_of_tag[node_tags[i]] = i;
        local_index.assign(max_tag + 1, invalid);
      }

      // The triangles of @p surface, counter-clockwise, as deal.II wants
      // them (the shoelace formula, as build_body_mesh evaluates it).
      void
      add_triangles(const int surface, const types::material_id material_id)
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

      // The line elements of gmsh curve @p tag, with boundary id @p id
      // (the triangles must have been added).
      void
      add_lines(const int                tag,
                const types::boundary_id id,
                const std::string       &body_name)
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
              line.boundary_id = id;
              mesh.boundary_lines.boundary_lines.push_back(line);
            }
      }

      CoarseMeshData mesh;

    private:
      static constexpr unsigned int invalid = numbers::invalid_unsigned_int;

      // The index of node @p tag in mesh.vertices, added at its first use.
      unsigned int
      vertex(const std::size_t tag)
      {
        if (local_index[tag] == invalid)
          {
            local_index[tag]    = mesh.vertices.size();
            const std::size_t i = node_of_tag[tag];
            mesh.vertices.emplace_back(coordinates[3 * i],
                                       coordinates[3 * i + 1]);
          }
        return local_index[tag];
      }

      std::vector<std::size_t>  node_tags;
      std::vector<double>       coordinates;
      std::vector<std::size_t>  node_of_tag;
      std::vector<unsigned int> local_index;
    };



    // Mesh in gmsh; the elements and the boundary lines of each curve.
    CoarseMeshData
    mesh_in_gmsh(const Triangulation<2>                     &geometry,
                 const std::vector<SizeFieldTriangle>       &size_field,
                 const std::string                          &body_name,
                 const int                                   algorithm,
                 const std::vector<std::array<Point<2>, 2>> &interior_lines,
                 const std::vector<Point<2>>                &support_points)
    {
      const auto features =
        interior_features(geometry, body_name, interior_lines, support_points);
      const auto boundary = loop_curves(geometry, body_name, features.corners);
      const auto gmsh_geometry =
        add_geometry(geometry, boundary, features, body_name);
      set_background_size_field(size_field);
      gmsh::option::setNumber("Mesh.Algorithm", algorithm);
      gmsh::model::mesh::generate(2);

      MeshFromGmsh from_gmsh;
      for (const int surface : gmsh_geometry.surfaces)
        from_gmsh.add_triangles(surface,
                                geometry.begin_active()->material_id());
      // Lines by curve, each curve's in gmsh's order, then the curve's
      // boundary and manifold ids.
      std::map<unsigned int, std::vector<int>> tags_of_curve;
      for (const auto &[tag, c] : gmsh_geometry.curve_index)
        tags_of_curve[c].push_back(tag);
      for (const auto &[c, tags] : tags_of_curve)
        for (const int tag : tags)
          from_gmsh.add_lines(tag, c, body_name);
      CoarseMeshData mesh = std::move(from_gmsh.mesh);
      for (auto &line : mesh.boundary_lines.boundary_lines)
        {
          const Curve &curve = boundary.curves[line.boundary_id];
          line.boundary_id   = curve.boundary_id;
          line.manifold_id   = curve.manifold_id;
        }
      put_nodes_on_curves(geometry, mesh);
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



  GmshMeshing
  mesh_with_gmsh_here(
    const Triangulation<2>                     &geometry,
    const std::vector<SizeFieldTriangle>       &size_field,
    const std::string                          &body_name,
    const RemeshingAlgorithm                    algorithm,
    const std::vector<std::array<Point<2>, 2>> &interior_lines,
    const std::vector<Point<2>>                &support_points,
    const unsigned int                          n_splits)
  {
    // gmsh's Mesh.Algorithm numbers.
    const int algorithm_number =
      algorithm == RemeshingAlgorithm::delaunay ? 5 : 6;
    GmshMeshing result;
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
    try
      {
        CoarseMeshData mesh = mesh_in_gmsh(geometry,
                                           size_field,
                                           body_name,
                                           algorithm_number,
                                           interior_lines,
                                           support_points);
        split_triangles(mesh, geometry, n_splits);
        result.packed_mesh = pack(mesh);
      }
    catch (const std::exception &e)
      {
        result.error = e.what();
      }
    catch (const std::string &thrown)
      {
        result.error = "gmsh: " + gmsh_error_message(thrown);
      }
    catch (...)
      {
        result.error = "gmsh: " + gmsh_error_message("");
      }
    gmsh::finalize();
    return result;
  }



  CoarseMeshData
  share_gmsh_mesh(const GmshMeshing &meshing,
                  const std::string &body_name,
                  const MPI_Comm     comm,
                  const unsigned int root)
  {
    const std::string error =
      Utilities::MPI::broadcast(comm, meshing.error, root);
    AssertThrow(error.empty(),
                ExcMessage("remeshing " + body_name + " failed: " + error));
    return unpack(Utilities::MPI::broadcast(comm, meshing.packed_mesh, root));
  }



  CoarseMeshData
  remesh_with_gmsh(const Triangulation<2>                     &geometry,
                   const std::vector<SizeFieldTriangle>       &size_field,
                   const std::string                          &body_name,
                   const MPI_Comm                              comm,
                   const RemeshingAlgorithm                    algorithm,
                   const std::vector<std::array<Point<2>, 2>> &interior_lines,
                   const std::vector<Point<2>>                &support_points)
  {
    // One rank meshes (gmsh is serial), every rank gets the mesh.
    GmshMeshing meshing;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      meshing = mesh_with_gmsh_here(geometry,
                                    size_field,
                                    body_name,
                                    algorithm,
                                    interior_lines,
                                    support_points);
    return share_gmsh_mesh(meshing, body_name, comm, 0);
  }
} // namespace coulomb_adapt
