#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/scenes/gmsh_bodies.h>
#include <coulomb_adapt/scenes/gmsh_model.h>

#include <gmsh.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace coulomb_adapt
{
  namespace gmsh_model
  {
    namespace
    {
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
    } // namespace



    GmshBodies::GmshBodies(const std::string  &file_name,
                           const GmshGroupUse &use,
                           const CellType      requested_cell_type,
                           const double        mesh_size_factor)
      : file_name(file_name)
      , in_file("gmsh file '" + file_name + "'")
    {
      open(requested_cell_type, mesh_size_factor);
      check_two_dimensional();
      read_nodes();
      read_circle_arcs();
      read_sampled_curves();
      groups = physical_groups_by_name(file_name);
      read_bodies(use);
    }



    // A .geo file is a geometry: gmsh meshes it here, with quadrangles if
    // asked for.
    void
    GmshBodies::open(const CellType requested_cell_type,
                     const double   mesh_size_factor) const
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
    }



    // The program is two-dimensional: a volume mesh would otherwise be
    // read as its projection.
    void
    GmshBodies::check_two_dimensional() const
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



    // The nodes, which must lie in the x-y plane (nodes off it would be
    // read as their projection).
    void
    GmshBodies::read_nodes()
    {
      std::vector<std::size_t> node_tags;
      std::vector<double>      coordinates, parametric;
      gmsh::model::mesh::getNodes(
        node_tags, coordinates, parametric, -1, -1, false, false);
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
    }



    // The circle arcs of the geometry (gmsh's curves of type "Circle"; a
    // .msh file's curves are discrete and have none): each circle's
    // centre, from three points of the curve, and its mesh lines. Circles
    // of one centre share a manifold id (deal.II's SphericalManifold does
    // not depend on the radius).
    void
    GmshBodies::read_circle_arcs()
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
          gmsh::model::getValue(
            dim, tag, {low[0], low[0] + span / 3, low[0] + 2 * span / 3}, xyz);
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



    namespace
    {
      // gmsh's types of the smooth curves that are sampled: a .geo's
      // Spline, BSpline, Bezier and Nurbs (gmsh 4.8 calls all of its own
      // kernel's "Nurb"), the OpenCASCADE kernel's B-splines and Bezier
      // curves, and ellipse arcs of either kernel.
      bool
      is_sampled_type(const std::string &type)
      {
        return type == "Nurb" || type == "BSpline" || type == "Bezier" ||
               type == "Ellipse";
      }



      // gmsh's points and derivatives of curve @p tag at @p parameters.
      void
      evaluate(const int                  tag,
               const std::vector<double> &parameters,
               std::vector<Point<2>>     &points,
               std::vector<Tensor<1, 2>> &derivatives)
      {
        std::vector<double> xyz, d;
        gmsh::model::getValue(1, tag, parameters, xyz);
        gmsh::model::getDerivative(1, tag, parameters, d);
        points.resize(parameters.size());
        derivatives.resize(parameters.size());
        for (std::size_t i = 0; i < parameters.size(); ++i)
          {
            points[i]      = Point<2>(xyz[3 * i], xyz[3 * i + 1]);
            derivatives[i] = Tensor<1, 2>({d[3 * i], d[3 * i + 1]});
          }
      }



      struct CurveSample
      {
        Point<2>     point;
        Tensor<1, 2> derivative;
      };



      // The samples in the order of gmsh's parameter; a closed curve (its
      // ends within @p tolerance) ends exactly where it starts.
      CurveSamples
      ordered_samples(const std::map<double, CurveSample> &samples,
                      const double                         tolerance)
      {
        CurveSamples result;
        for (const auto &[t, sample] : samples)
          {
            result.parameters.push_back(t);
            result.points.push_back(sample.point);
            result.derivatives.push_back(sample.derivative);
          }
        if (result.points.front().distance(result.points.back()) <= tolerance)
          {
            result.closed        = true;
            result.points.back() = result.points.front();
          }
        return result;
      }



      // Curve @p tag sampled so that the cubic Hermite interpolation of
      // the samples (CurveManifold) is the curve to @p tolerance: 64
      // intervals of gmsh's parameter, then every interval whose
      // interpolant is farther than @p tolerance from the curve at a
      // quarter, the middle or three quarters of it is halved, until none
      // is (at most 16384 samples). On a smooth piece the error falls as
      // h^4; around a knot of a spline where the second derivative jumps
      // (gmsh's Spline is C1), as h^2, so the halving concentrates there.
      CurveSamples
      sample_curve(const int tag, const double tolerance)
      {
        std::vector<double> low, high;
        gmsh::model::getParametrizationBounds(1, tag, low, high);
        std::map<double, CurveSample> samples;
        std::vector<double>           first;
        const unsigned int            n_first = 64;
        for (unsigned int i = 0; i <= n_first; ++i)
          first.push_back(
            i == n_first ? high[0] : low[0] + (high[0] - low[0]) * i / n_first);
        std::vector<Point<2>>     points;
        std::vector<Tensor<1, 2>> derivatives;
        evaluate(tag, first, points, derivatives);
        std::vector<double> to_check;
        for (unsigned int i = 0; i <= n_first; ++i)
          {
            samples[first[i]] = {points[i], derivatives[i]};
            if (i < n_first)
              to_check.push_back(first[i]);
          }

        const std::size_t max_samples = 16384;
        const double      fractions[] = {0.25, 0.5, 0.75};
        while (!to_check.empty() && samples.size() < max_samples)
          {
            std::vector<double> tests;
            for (const double t : to_check)
              {
                const double next = std::next(samples.find(t))->first;
                for (const double q : fractions)
                  tests.push_back(t + q * (next - t));
              }
            evaluate(tag, tests, points, derivatives);
            std::vector<std::size_t> halved;
            for (std::size_t i = 0; i < to_check.size(); ++i)
              {
                const auto   a       = samples.find(to_check[i]);
                const auto   b       = std::next(a);
                const double h       = b->first - a->first;
                bool         too_far = false;
                for (unsigned int k = 0; k < 3; ++k)
                  too_far =
                    too_far || cubic_hermite(a->second.point,
                                             a->second.derivative,
                                             b->second.point,
                                             b->second.derivative,
                                             h,
                                             fractions[k])
                                   .distance(points[3 * i + k]) > tolerance;
                if (too_far)
                  halved.push_back(i);
              }
            to_check.clear();
            if (samples.size() + halved.size() > max_samples)
              break;
            for (const std::size_t i : halved)
              {
                const double middle = tests[3 * i + 1];
                samples[middle] = {points[3 * i + 1], derivatives[3 * i + 1]};
                to_check.push_back(std::prev(samples.find(middle))->first);
                to_check.push_back(middle);
              }
          }

        return ordered_samples(samples, tolerance);
      }
    } // namespace



    // The other smooth curves of the geometry (splines, B-splines, Bezier
    // curves, ellipses): sampled through gmsh's parametrisation while gmsh
    // has the model (CurveSamples), each with its own manifold id after
    // those of the circles, to 1e-10 of the model's size.
    void
    GmshBodies::read_sampled_curves()
    {
      gmsh::vectorpair curves;
      gmsh::model::getEntities(curves, 1);
      types::manifold_id next_id = 0;
      for (const auto &[id, centre] : circle_centres)
        next_id = std::max<types::manifold_id>(next_id, id + 1);
      for (const auto &[dim, tag] : curves)
        {
          std::string type;
          gmsh::model::getType(dim, tag, type);
          if (!is_sampled_type(type))
            continue;
          const auto lines = elements_of_entities(1, {tag}, file_name);
          if (lines.empty())
            continue;
          sampled_curves.emplace(next_id, sample_curve(tag, 1e-10 * extent));
          for (const auto &line : lines)
            curved_edges[edge_of(line[0], line[1])] = next_id;
          ++next_id;
        }
    }



    // The entities of group @p name, which @p entry names and which must
    // have dimension @p dim.
    std::vector<int>
    GmshBodies::entities_of(const std::string &name,
                            const int          dim,
                            const std::string &entry,
                            const std::string &why) const
    {
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
      gmsh::model::getEntitiesForPhysicalGroup(dim, group->second.second, tags);
      return tags;
    }



    // An element may name a node that the file does not define (a
    // hand-edited or truncated file); gmsh does not check it.
    void
    GmshBodies::require_known_nodes(
      const std::vector<std::vector<std::size_t>> &elements,
      const std::string                           &what) const
    {
      for (const auto &element : elements)
        for (const std::size_t node : element)
          if (nodes.count(node) == 0)
            throw ParameterError(in_file + ": " + what + " refers to node " +
                                 std::to_string(node) +
                                 ", which is not in $Nodes");
    }



    // The bodies: their surfaces, none in both.
    void
    GmshBodies::read_bodies(const GmshGroupUse &use)
    {
      std::map<int, std::pair<unsigned int, std::string>> body_of_surface;
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
    }



    // The lines of the curve group @p name, with the curve each comes from.
    GmshBodies::Lines
    GmshBodies::lines_of(const std::string &name,
                         const std::string &entry,
                         const std::string &why) const
    {
      Lines lines;
      for (const int curve : entities_of(name, 1, entry, why))
        for (const auto &line : elements_of_entities(1, {curve}, file_name))
          {
            require_known_nodes({line}, "a line element of '" + name + "'");
            lines.emplace_back(edge_of(line[0], line[1]), curve);
          }
      return lines;
    }



    // How many of @p lines lie on the boundary of body @p b.
    unsigned int
    GmshBodies::count_on(const Lines &lines, const unsigned int b) const
    {
      unsigned int n = 0;
      for (const auto &line : lines)
        n += body_boundary[b].count(line.first);
      return n;
    }
  } // namespace gmsh_model
} // namespace coulomb_adapt
