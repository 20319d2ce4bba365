#include <coulomb_adapt/indicator/local_problem_loads.h>

namespace coulomb_adapt
{
  namespace equilibration
  {
    LocalProblemLoads::LocalProblemLoads(const BodyDescription &description,
                                         const std::vector<CellData> &cells,
                                         const std::vector<FaceData> &faces,
                                         const ContactTractionData   &contact,
                                         const unsigned int           fe_degree,
                                         const unsigned int local_degree)
      : cells(cells)
      , faces(faces)
      , contact(contact)
      , fe_degree(fe_degree)
      , edge_rule(local_degree + 2)
    {
      for (const auto &t : description.tractions)
        traction_on[t.boundary_id] = &t.traction;
    }



    void
    LocalProblemLoads::add_face_polynomial(
      const LocalNeumannProblem                &local,
      Vector<double>                           &load,
      const FaceData                           &face,
      const std::vector<std::array<double, 2>> &coefficients,
      const double                              sign,
      const std::array<bool, 2>                &mask) const
    {
      for (unsigned int q = 0; q < edge_rule.size(); ++q)
        {
          const double s   = edge_rule.point(q)[0];
          const auto   phi = face_shape_values(face.s, s);
          Tensor<1, 2> F;
          for (unsigned int k = 0; k < face.nodes.size(); ++k)
            for (unsigned int c = 0; c < 2; ++c)
              F[c] += phi[k] * coefficients[k][c];
          // At the face's point (on a curved face, off the chord), with
          // the chord's length element: the coefficients are those the node
          // systems solved for with the edge mass matrix in that measure.
          local.add_traction(load,
                             face_point(face, s),
                             sign * F,
                             edge_rule.weight(q) * face.length,
                             mask);
        }
    }



    void
    LocalProblemLoads::face_work(const LocalNeumannProblem &local,
                                 const unsigned int         slot,
                                 const FaceData            &face,
                                 FullMatrix<double>        &W) const
    {
      const unsigned int n   = face.nodes.size();
      const unsigned int M   = local.n_coefficients() / 2;
      const double       eta = face.plus == static_cast<int>(slot) ? 1 : -1;
      W.reinit(M, n + 3);
      for (unsigned int q = 0; q < edge_rule.size(); ++q)
        {
          const double s      = edge_rule.point(q)[0];
          const auto   phi    = face_shape_values(face.s, s);
          const double L      = edge_bubble(fe_degree + 1, s);
          const double P1     = edge_bubble(1, s);
          const double P2     = edge_bubble(2, s);
          const double w      = eta * edge_rule.weight(q) * face.length;
          const auto  &values = local.monomial_values(face_point(face, s));
          for (unsigned int m = 0; m < M; ++m)
            {
              for (unsigned int j = 0; j < n; ++j)
                W(m, j) += phi[j] * values[m] * w;
              W(m, n) += L * values[m] * w;
              W(m, n + 1) += P1 * values[m] * w;
              W(m, n + 2) += P2 * values[m] * w;
            }
        }
    }



    void
    LocalProblemLoads::cell_load(const LocalNeumannProblem &local,
                                 const unsigned int         slot,
                                 Vector<double>            &load) const
    {
      const auto &cell = cells[slot].cell;
      load             = local.body_force_load();
      for (const unsigned int f : cell->face_indices())
        {
          const FaceData           &face   = faces[cells[slot].faces[f]];
          const std::array<bool, 2> solved = {
            {face.unknown[0], face.unknown[1]}};
          if (solved[0] || solved[1])
            add_face_polynomial(local,
                                load,
                                face,
                                face.coefficients,
                                face.plus == static_cast<int>(slot) ? 1 : -1,
                                solved);
          const std::array<bool, 2> prescribed = {{!solved[0], !solved[1]}};
          if (face.at_boundary && (prescribed[0] || prescribed[1]))
            {
              const auto t = traction_on.find(cell->face(f)->boundary_id());
              if (t != traction_on.end())
                for (unsigned int q = 0; q < edge_rule.size(); ++q)
                  {
                    const FacePointGeometry g =
                      face_geometry(face, edge_rule.point(q)[0]);
                    local.add_traction(load,
                                       g.point,
                                       (*t->second)(g.point, g.normal),
                                       edge_rule.weight(q) * g.length_element,
                                       prescribed);
                  }
            }
        }
      // A held line's traction g, the same on both sides of its faces.
      for (const unsigned int f : cell->face_indices())
        {
          const FaceData &face = faces[cells[slot].faces[f]];
          if (!face.held_coefficients.empty())
            add_face_polynomial(
              local, load, face, face.held_coefficients, 1, {{true, true}});
        }
      if (const auto c = contact.find(cell->id()); c != contact.end())
        for (const auto &point : c->second)
          local.add_traction(
            load, point.point, point.traction, point.weight, {{true, true}});
    }
  } // namespace equilibration
} // namespace coulomb_adapt
