#include <deal.II/base/mpi.h>

#include <coulomb_adapt/adaptation/contact_size_cap.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace coulomb_adapt
{
  namespace
  {
    using VertexKey = std::pair<double, double>;

    // The faces of @p body's contact boundary as (x0, y0, x1, y1), on
    // every rank, in a fixed order; @p curved: whether one of them lies on
    // a curved manifold (on every rank).
    std::vector<std::array<double, 4>>
    contact_faces(const ElasticBody &body, bool &curved)
    {
      const types::boundary_id contact = body.description().contact_boundary_id;
      std::vector<std::array<double, 4>> local;
      unsigned int                       local_curved = 0;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == contact)
              {
                local.push_back({{face->vertex(0)[0],
                                  face->vertex(0)[1],
                                  face->vertex(1)[0],
                                  face->vertex(1)[1]}});
                if (face->manifold_id() != numbers::flat_manifold_id)
                  local_curved = 1;
              }
      const MPI_Comm comm = body.dof_handler().get_communicator();
      curved              = Utilities::MPI::max(local_curved, comm) == 1;
      std::vector<std::array<double, 4>> faces;
      for (const auto &part : Utilities::MPI::all_gather(comm, local))
        faces.insert(faces.end(), part.begin(), part.end());
      std::sort(faces.begin(), faces.end());
      return faces;
    }



    // The size at each vertex of a field.
    std::map<VertexKey, double>
    vertex_sizes(const std::vector<SizeFieldTriangle> &field)
    {
      std::map<VertexKey, double> sizes;
      for (const auto &t : field)
        for (unsigned int v = 0; v < 3; ++v)
          sizes[{t.vertices[v][0], t.vertices[v][1]}] = t.size[v];
      return sizes;
    }



    // A slave contact face with the slave's sizes at its ends.
    struct SizedSegment
    {
      Point<2> a, b;
      double   size_a, size_b;
    };

    // The slave's contact faces with the sizes of its field (on @p root,
    // where the field is), on every rank.
    std::vector<SizedSegment>
    slave_segments(const std::vector<std::array<double, 4>> &faces,
                   const std::vector<SizeFieldTriangle>     &field,
                   const MPI_Comm                            comm,
                   const unsigned int                        root)
    {
      std::vector<double> packed;
      if (Utilities::MPI::this_mpi_process(comm) == root)
        {
          const auto sizes = vertex_sizes(field);
          for (const auto &f : faces)
            packed.insert(packed.end(),
                          {f[0],
                           f[1],
                           sizes.at({f[0], f[1]}),
                           f[2],
                           f[3],
                           sizes.at({f[2], f[3]})});
        }
      packed = Utilities::MPI::broadcast(comm, packed, root);
      std::vector<SizedSegment> segments;
      for (std::size_t k = 0; k + 5 < packed.size(); k += 6)
        segments.push_back({Point<2>(packed[k], packed[k + 1]),
                            Point<2>(packed[k + 3], packed[k + 4]),
                            packed[k + 2],
                            packed[k + 5]});
      return segments;
    }



    // The slave's size at the point of its contact boundary nearest to
    // @p x (linear along a face), and the distance to it.
    std::pair<double, double>
    slave_size_near(const std::vector<SizedSegment> &segments,
                    const Point<2>                  &x)
    {
      double distance = std::numeric_limits<double>::max(), size = 0;
      for (const auto &s : segments)
        {
          const Tensor<1, 2> edge   = s.b - s.a;
          const double       length = edge.norm_square();
          const double       t =
            length > 0 ? std::clamp((x - s.a) * edge / length, 0., 1.) : 0.;
          const double d = x.distance(s.a + t * edge);
          if (d < distance)
            {
              distance = d;
              size     = (1 - t) * s.size_a + t * s.size_b;
            }
        }
      return {size, distance};
    }



    // The capped master contact vertices: where the slave faces the
    // master vertex (within the master's own size there) and the master is
    // coarser than the ratio allows.
    std::vector<std::pair<Point<2>, double>>
    master_caps(const std::vector<std::array<double, 4>> &master_faces,
                const std::map<VertexKey, double>        &master_sizes,
                const std::vector<SizedSegment>          &slave)
    {
      std::map<VertexKey, double> caps;
      for (const auto &f : master_faces)
        for (const VertexKey &vertex :
             {VertexKey{f[0], f[1]}, VertexKey{f[2], f[3]}})
          {
            const auto own = master_sizes.find(vertex);
            if (own == master_sizes.end() || caps.count(vertex) > 0)
              continue;
            const auto [size, distance] =
              slave_size_near(slave, Point<2>(vertex.first, vertex.second));
            const double cap = master_to_slave_size_ratio * size;
            if (distance <= own->second && cap < own->second)
              caps[vertex] = cap;
          }
      std::vector<std::pair<Point<2>, double>> result;
      for (const auto &[vertex, cap] : caps)
        result.emplace_back(Point<2>(vertex.first, vertex.second), cap);
      return result;
    }
  } // namespace



  void
  cap_master_contact_sizes(
    const std::array<ElasticBody *, 2>            &bodies,
    const std::array<unsigned int, 2>             &root,
    std::array<std::vector<SizeFieldTriangle>, 2> &fields)
  {
    // Only the master's curvature matters: its chords' kinks.
    bool       slave_curved = false, master_curved = false;
    const auto slave_faces  = contact_faces(*bodies[0], slave_curved);
    const auto master_faces = contact_faces(*bodies[1], master_curved);
    if (!master_curved || slave_faces.empty())
      return;
    const MPI_Comm comm = bodies[0]->dof_handler().get_communicator();
    const auto slave    = slave_segments(slave_faces, fields[0], comm, root[0]);
    if (Utilities::MPI::this_mpi_process(comm) != root[1])
      return;

    auto       sizes = vertex_sizes(fields[1]);
    const auto caps  = master_caps(master_faces, sizes, slave);
    if (caps.empty())
      return;
    // Each vertex of the field: the smallest of its size and the graded
    // caps, h <= cap + grading |x - y|. Rounded to float as the field is
    // (size_field.cc: the mesh must not depend on the number of ranks).
    for (auto &[vertex, h] : sizes)
      {
        const Point<2> x(vertex.first, vertex.second);
        for (const auto &[y, cap] : caps)
          h = std::min(h, cap + contact_size_grading * x.distance(y));
        h = static_cast<float>(h);
      }
    for (auto &t : fields[1])
      for (unsigned int v = 0; v < 3; ++v)
        t.size[v] = sizes.at({t.vertices[v][0], t.vertices[v][1]});
  }
} // namespace coulomb_adapt
