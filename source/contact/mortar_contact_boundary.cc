#include <deal.II/base/mpi.h>

#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/contact/segment_curve.h>

#include <algorithm>
#include <map>

// The first half of the mortar interface: each side's contact boundary
// as nodes and segments, gathered from all ranks, numbered independently
// of the partition, with nodal normals. The integrals of D, M and g~ on
// these segments are in mortar_interface.cc.

namespace coulomb_adapt
{
  namespace mortar
  {
    SegmentCurve
    segment_curve(const std::vector<MortarInterface::Node> &nodes,
                  const MortarInterface::Segment           &segment,
                  const unsigned int                        degree)
    {
      SegmentCurve curve{{}, degree};
      for (const unsigned int n : segment.nodes)
        curve.points.push_back(nodes[n].position);
      return curve;
    }
  } // namespace mortar



  namespace
  {
    using namespace mortar;
    using Node    = MortarInterface::Node;
    using Segment = MortarInterface::Segment;

    // The outward unit normal of a face's chord: the segment's normal on
    // straight faces, and the side a curved face's normal is taken on.
    template <typename CellIterator, typename FaceIterator>
    Tensor<1, 2>
    outward_chord_normal(const CellIterator &cell, const FaceIterator &face)
    {
      const Tensor<1, 2> edge = face->vertex(1) - face->vertex(0);
      Tensor<1, 2>       normal({edge[1], -edge[0]});
      normal /= normal.norm();
      if ((face->center() - cell->center()) * normal < 0)
        normal = -normal;
      return normal;
    }

    // Every rank's contact faces in one flat list of doubles, so that one
    // all_gather gives each rank the whole boundary. Per face: for each
    // node (x, y, dof_x, dof_y), then the outward normal of the face's
    // chord and the cell's id (4 integers, exact in doubles); for degree 1
    // then the manifold's midpoint of the face.
    std::vector<double>
    pack_local_contact_faces(const DoFHandler<2>     &dof_handler,
                             const types::boundary_id contact_id,
                             const unsigned int       degree)
    {
      std::vector<double> local;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == contact_id)
              {
                const Tensor<1, 2> normal = outward_chord_normal(cell, face);
                for (unsigned int v = 0; v < 2; ++v)
                  local.insert(local.end(),
                               {face->vertex(v)[0],
                                face->vertex(v)[1],
                                double(face->vertex_dof_index(v, 0)),
                                double(face->vertex_dof_index(v, 1))});
                if (degree == 2)
                  {
                    // The edge node, on the boundary's manifold (where the
                    // element's mapping puts it).
                    const Point<2> middle = face->center(true);
                    local.insert(local.end(),
                                 {middle[0],
                                  middle[1],
                                  double(face->dof_index(0)),
                                  double(face->dof_index(1))});
                  }
                local.push_back(normal[0]);
                local.push_back(normal[1]);
                for (const unsigned int id : cell->id().to_binary<2>())
                  local.push_back(id);
                if (degree == 1)
                  {
                    const Point<2> middle = face->center(true);
                    local.insert(local.end(), {middle[0], middle[1]});
                  }
              }
      return local;
    }

    // The gathered faces unpacked: the nodes once each (a node is
    // identified by its x DoF), and per face its nodes' x DoFs, its
    // chord's normal and its cell.
    struct GatheredBoundary
    {
      std::map<types::global_dof_index, Node>           unique_nodes;
      std::vector<std::vector<types::global_dof_index>> segment_dofs;
      std::vector<Tensor<1, 2>>                         segment_normals;
      std::vector<CellId>                               segment_cells;
      /** Degree 1: the faces' midpoints on their manifolds. */
      std::vector<Point<2>> segment_middles;
    };

    GatheredBoundary
    unpack_contact_faces(const std::vector<std::vector<double>> &gathered,
                         const unsigned int                      n_face_nodes)
    {
      const bool         linear = n_face_nodes == 2;
      const unsigned int record = 4 * n_face_nodes + 6 + (linear ? 2 : 0);
      GatheredBoundary   boundary;
      for (const auto &values : gathered)
        for (std::size_t i = 0; i < values.size(); i += record)
          {
            std::vector<types::global_dof_index> face_nodes;
            for (unsigned int v = 0; v < n_face_nodes; ++v)
              {
                Node node;
                node.position =
                  Point<2>(values[i + 4 * v], values[i + 4 * v + 1]);
                node.dofs = {
                  {static_cast<types::global_dof_index>(values[i + 4 * v + 2]),
                   static_cast<types::global_dof_index>(
                     values[i + 4 * v + 3])}};
                face_nodes.push_back(node.dofs[0]);
                boundary.unique_nodes.emplace(node.dofs[0], node);
              }
            boundary.segment_dofs.push_back(face_nodes);
            const std::size_t n = i + 4 * n_face_nodes;
            boundary.segment_normals.emplace_back(
              Tensor<1, 2>({values[n], values[n + 1]}));
            CellId::binary_type id;
            for (unsigned int k = 0; k < 4; ++k)
              id[k] = static_cast<unsigned int>(values[n + 2 + k]);
            boundary.segment_cells.emplace_back(id);
            if (linear)
              boundary.segment_middles.emplace_back(values[n + 6],
                                                    values[n + 7]);
          }
      return boundary;
    }

    // The nodes in lexicographic order of their positions, so that the
    // numbering does not depend on the number of ranks.
    std::vector<Node>
    lexicographic_nodes(
      const std::map<types::global_dof_index, Node> &unique_nodes)
    {
      std::vector<Node> nodes;
      for (const auto &[dof, node] : unique_nodes)
        nodes.push_back(node);
      std::sort(nodes.begin(), nodes.end(), [](const Node &a, const Node &b) {
        return a.position[0] < b.position[0] ||
               (a.position[0] == b.position[0] &&
                a.position[1] < b.position[1]);
      });
      return nodes;
    }

    // The segments on the numbered nodes, in the order of their first
    // node, so that the sums over segments are reproducible.
    std::vector<Segment>
    numbered_segments(const GatheredBoundary  &boundary,
                      const std::vector<Node> &nodes,
                      const unsigned int       degree)
    {
      std::map<types::global_dof_index, unsigned int> index_of;
      for (unsigned int n = 0; n < nodes.size(); ++n)
        index_of[nodes[n].dofs[0]] = n;

      std::vector<Segment> segments;
      for (unsigned int s = 0; s < boundary.segment_dofs.size(); ++s)
        {
          Segment segment;
          for (const auto dof : boundary.segment_dofs[s])
            segment.nodes.push_back(index_of[dof]);
          segment.normal = boundary.segment_normals[s];
          segment.cell   = boundary.segment_cells[s];
          if (degree == 1)
            {
              const Point<2> &a       = nodes[segment.nodes[0]].position,
                             &b       = nodes[segment.nodes[1]].position;
              segment.manifold_middle = boundary.segment_middles[s];
              segment.on_curved_manifold =
                segment.manifold_middle.distance(a + 0.5 * (b - a)) >
                1e-10 * a.distance(b);
            }
          if (degree == 2)
            {
              // A middle node off the chord's midpoint (on a curved
              // manifold) makes the face a parabola.
              const Point<2> &a = nodes[segment.nodes[0]].position,
                             &b = nodes[segment.nodes[1]].position,
                             &m = nodes[segment.nodes[2]].position;
              segment.curved =
                m.distance(a + 0.5 * (b - a)) > 1e-10 * a.distance(b);
            }
          segments.push_back(segment);
        }
      std::sort(segments.begin(),
                segments.end(),
                [](const Segment &a, const Segment &b) {
                  return std::min(a.nodes[0], a.nodes[1]) <
                         std::min(b.nodes[0], b.nodes[1]);
                });
      return segments;
    }

    // Nodal normals: the average of the adjacent segments' normals (on a
    // curved segment its curve's normal at the node), and the tangents.
    void
    set_nodal_normals(std::vector<Node>          &nodes,
                      const std::vector<Segment> &segments,
                      const unsigned int          degree)
    {
      for (auto &node : nodes)
        node.normal = Tensor<1, 2>();
      for (const auto &segment : segments)
        for (unsigned int i = 0; i < segment.nodes.size(); ++i)
          if (segment.curved)
            {
              const SegmentCurve curve = segment_curve(nodes, segment, degree);
              nodes[segment.nodes[i]].normal +=
                curve.normal(i == 2 ? 0.5 : double(i), segment.normal);
            }
          else
            nodes[segment.nodes[i]].normal += segment.normal;
      for (auto &node : nodes)
        {
          node.normal /= node.normal.norm();
          node.tangent = Tensor<1, 2>({-node.normal[1], node.normal[0]});
        }
    }
  } // namespace



  unsigned int
  MortarInterface::collect_contact_boundary(const ElasticBody    &body,
                                            std::vector<Node>    &nodes,
                                            std::vector<Segment> &segments)
  {
    const DoFHandler<2> &dof_handler = body.dof_handler();
    const unsigned int   degree      = dof_handler.get_fe().degree;
    AssertThrow(degree <= 2,
                ExcMessage("The mortar contact interface supports degrees 1 "
                           "and 2."));

    const auto gathered = Utilities::MPI::all_gather(
      dof_handler.get_triangulation().get_communicator(),
      pack_local_contact_faces(dof_handler,
                               body.description().contact_boundary_id,
                               degree));
    const GatheredBoundary boundary =
      unpack_contact_faces(gathered, degree + 1);

    nodes    = lexicographic_nodes(boundary.unique_nodes);
    segments = numbered_segments(boundary, nodes, degree);
    set_nodal_normals(nodes, segments, degree);
    return degree;
  }
} // namespace coulomb_adapt
