#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/indicator/dirichlet_data_lift.h>

#include <algorithm>
#include <array>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    // The polynomial of degree nodes.size() - 1 through (nodes[k],
    // values[k]), and its derivative, at t (Lagrange form: a handful of
    // nodes).
    std::array<double, 2>
    interpolant(const std::vector<double> &nodes,
                const std::vector<double> &values,
                const double               t)
    {
      double value = 0, derivative = 0;
      for (unsigned int k = 0; k < nodes.size(); ++k)
        {
          double basis = 1, basis_derivative = 0;
          for (unsigned int j = 0; j < nodes.size(); ++j)
            if (j != k)
              {
                const double factor = 1. / (nodes[k] - nodes[j]);
                basis_derivative =
                  basis_derivative * (t - nodes[j]) * factor + basis * factor;
                basis *= (t - nodes[j]) * factor;
              }
          value += values[k] * basis;
          derivative += values[k] * basis_derivative;
        }
      return {{value, derivative}};
    }

    // One Dirichlet face of a cell: its vertices (cell-local numbers), the
    // constrained components and S's values at the interior nodes.
    struct LiftedFace
    {
      unsigned int                       a, b;
      std::array<bool, 2>                components = {{false, false}};
      std::array<std::vector<double>, 2> s_values;
    };
  } // namespace



  DirichletDataLift
  dirichlet_data_lift(const ElasticBody                   &body,
                      const TrilinosWrappers::MPI::Vector &u_kinematic)
  {
    DirichletDataLift lift;
    const auto       &tria = body.triangulation();
    lift.squared.reinit(tria.n_active_cells());
    const BodyDescription &description = body.description();
    if (description.displacement_data_interpolated_exactly ||
        description.dirichlet.empty())
      return lift;

    const auto        &fe = body.dof_handler().get_fe();
    const unsigned int p  = fe.degree;
    // S's nodes: p + 1 points inside the face, equally spaced.
    std::vector<double> nodes(p + 1);
    for (unsigned int k = 0; k <= p; ++k)
      nodes[k] = (k + 1.) / (p + 2.);
    // r has degree p + 2 on triangles (p + 2 per direction on
    // quadrilaterals, through N_a N_b); the energy integrand twice that
    // less 2. QGaussSimplex offers at most 4 points (degree 7) in deal.II
    // 9.4: enough for p <= 2.
    const ReferenceCell reference = body.is_simplex_mesh() ?
                                      ReferenceCells::Triangle :
                                      ReferenceCells::Quadrilateral;
    const Quadrature<2> cell_rule =
      body.is_simplex_mesh() ?
        Quadrature<2>(QGaussSimplex<2>(std::min(p + 2, 4u))) :
        Quadrature<2>(QGauss<2>(p + 4));
    FEValues<2>            cell_values(body.mapping(),
                            fe,
                            cell_rule,
                            update_inverse_jacobians | update_JxW_values);
    const ElasticMaterial &material = body.material();

    for (const auto &cell : body.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned() || !cell->at_boundary())
          continue;
        std::vector<LiftedFace> faces;
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            LiftedFace face;
            for (const auto &condition : description.dirichlet)
              if (condition.boundary_id == cell->face(f)->boundary_id())
                for (unsigned int c = 0; c < 2; ++c)
                  if (condition.components[c])
                    face.components[c] = true;
            if (!face.components[0] && !face.components[1])
              continue;
            face.a = reference.face_to_cell_vertices(f, 0, 1);
            face.b = reference.face_to_cell_vertices(f, 1, 1);
            // d = u_D - u_c at the interior nodes, divided by t (1 - t).
            std::vector<Point<2>> points(nodes.size());
            for (unsigned int k = 0; k < nodes.size(); ++k)
              points[k] =
                Point<2>((1 - nodes[k]) * reference.vertex<2>(face.a) +
                         nodes[k] * reference.vertex<2>(face.b));
            FEValues<2> face_values(body.mapping(),
                                    fe,
                                    Quadrature<2>(points),
                                    update_values | update_quadrature_points);
            face_values.reinit(cell);
            std::vector<Vector<double>> u_c(points.size(), Vector<double>(2));
            face_values.get_function_values(u_kinematic, u_c);
            for (unsigned int c = 0; c < 2; ++c)
              if (face.components[c])
                for (unsigned int k = 0; k < nodes.size(); ++k)
                  {
                    double u_d = 0;
                    for (const auto &condition : description.dirichlet)
                      if (condition.boundary_id ==
                            cell->face(f)->boundary_id() &&
                          condition.components[c])
                        u_d = condition.displacement->value(
                          face_values.quadrature_point(k), c);
                    face.s_values[c].push_back((u_d - u_c[k](c)) /
                                               (nodes[k] * (1 - nodes[k])));
                  }
            faces.push_back(face);
          }
        if (faces.empty())
          continue;

        cell_values.reinit(cell);
        double energy = 0;
        for (const unsigned int q : cell_values.quadrature_point_indices())
          {
            const Point<2> &xi = cell_rule.point(q);
            // The reference gradient of r's two components.
            std::array<Tensor<1, 2>, 2> gradient;
            for (const auto &face : faces)
              {
                const double N_a =
                  reference.d_linear_shape_function(xi, face.a);
                const double N_b =
                  reference.d_linear_shape_function(xi, face.b);
                const Tensor<1, 2> grad_a =
                  reference.d_linear_shape_function_gradient(xi, face.a);
                const Tensor<1, 2> grad_b =
                  reference.d_linear_shape_function_gradient(xi, face.b);
                for (unsigned int c = 0; c < 2; ++c)
                  if (face.components[c])
                    {
                      const auto [S, dS] =
                        interpolant(nodes, face.s_values[c], N_b);
                      gradient[c] += S * (N_b * grad_a + N_a * grad_b) +
                                     N_a * N_b * dS * grad_b;
                    }
              }
            // To the physical cell: d r / d x_i = sum_k d r / d xi_k
            // d xi_k / d x_i.
            const DerivativeForm<1, 2, 2> &inverse =
              cell_values.inverse_jacobian(q);
            SymmetricTensor<2, 2> strain;
            Tensor<2, 2>          grad_x;
            for (unsigned int c = 0; c < 2; ++c)
              for (unsigned int i = 0; i < 2; ++i)
                for (unsigned int k = 0; k < 2; ++k)
                  grad_x[c][i] += gradient[c][k] * inverse[k][i];
            strain = symmetrize(grad_x);
            energy += material.stress(strain) * strain * cell_values.JxW(q);
          }
        lift.squared(cell->active_cell_index()) = energy;
      }
    lift.norm_squared =
      Utilities::MPI::sum(lift.squared.l1_norm(), tria.get_communicator());
    return lift;
  }
} // namespace coulomb_adapt
