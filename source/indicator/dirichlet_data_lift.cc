#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/indicator/dirichlet_data_lift.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    // One Dirichlet face of a cell: its vertices (cell-local numbers), the
    // constrained components, and at each of the cell's quadrature points
    // g = d / (t (1 - t)) and dg/dt at t = N_b there.
    struct LiftedFace
    {
      unsigned int                       a, b;
      std::array<bool, 2>                components = {{false, false}};
      std::array<std::vector<double>, 2> g, dg;
    };

    // Whether a body's displacement data need the lift: there are some,
    // and the FE space does not interpolate them exactly.
    bool
    data_need_lift(const BodyDescription &description)
    {
      return !description.displacement_data_interpolated_exactly &&
             !description.dirichlet.empty();
    }
  } // namespace



  std::string
  data_gradient_mismatch(const Function<2> &data,
                         const unsigned int c,
                         const Point<2>    &a,
                         const Point<2>    &b)
  {
    const double       h       = a.distance(b);
    const Tensor<1, 2> tangent = (b - a) / h;
    const double       step    = 1e-3 * h;
    // Two points, not the centre alone: data symmetric about the centre
    // have a zero derivative there, which a missing gradient() matches.
    for (const double t : {0.25, 0.75})
      {
        const Point<2> x              = a + t * (b - a);
        const double   value          = data.value(x, c);
        const double   along_gradient = data.gradient(x, c) * tangent;
        const double   difference     = (data.value(x + step * tangent, c) -
                                   data.value(x - step * tangent, c)) /
                                  (2 * step);
        // How much the data vary along the face: a large constant part
        // of the values must not hide a wrong derivative on fine meshes;
        // round-off in the difference is about 1e-13 |value| / h.
        const double variation =
          std::max(std::abs(data.value(a, c) - value) / (t * h),
                   std::abs(data.value(b, c) - value) / ((1 - t) * h));
        const double scale = std::max({std::abs(along_gradient),
                                       std::abs(difference),
                                       variation,
                                       1e-10 * std::abs(value) / h,
                                       std::numeric_limits<double>::min()});
        if (std::abs(along_gradient - difference) > 1e-5 * scale)
          {
            std::ostringstream message;
            message << "the displacement data's gradient() gives the "
                       "derivative "
                    << along_gradient << " along the face at (" << x
                    << ") in component " << c << ", its values " << difference
                    << " (central difference)";
            return message.str();
          }
      }
    return "";
  }



  DirichletDataLiftField::DirichletDataLiftField(
    const ElasticBody                   &body,
    const TrilinosWrappers::MPI::Vector &u_kinematic)
    : body(body)
    , u_kinematic(u_kinematic)
  {}



  void
  check_displacement_data_gradient(const ElasticBody &body)
  {
    if (!data_need_lift(body.description()))
      return;
    // Every Dirichlet face this rank owns (a few function values each),
    // until one disagrees; the verdict is every rank's, so all stop
    // together.
    std::string mismatch;
    for (const auto &cell : body.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary())
              continue;
            for (const auto &condition : body.description().dirichlet)
              if (condition.boundary_id == face->boundary_id())
                for (unsigned int c = 0; c < 2; ++c)
                  if (condition.components[c] && mismatch.empty())
                    mismatch = data_gradient_mismatch(*condition.displacement,
                                                      c,
                                                      face->vertex(0),
                                                      face->vertex(1));
          }
    const MPI_Comm comm = body.triangulation().get_communicator();
    for (const std::string &m : Utilities::MPI::all_gather(comm, mismatch))
      AssertThrow(m.empty(),
                  ExcMessage("body '" + body.name() +
                             "': 'Error indicator/CRE lift of displacement "
                             "data' lifts the displacement data's "
                             "interpolation error and needs their gradient, "
                             "but " +
                             m +
                             ". Implement the data Function's gradient() in "
                             "the scene, or set 'CRE lift of displacement "
                             "data = false'."));
  }



  bool
  DirichletDataLiftField::active() const
  {
    return data_need_lift(body.description());
  }



  std::vector<Tensor<2, 2>>
  DirichletDataLiftField::gradients(
    const DoFHandler<2>::active_cell_iterator &cell,
    const std::vector<Point<2>>               &points) const
  {
    std::vector<Tensor<2, 2>> result;
    if (!active() || !cell->at_boundary())
      return result;
    const BodyDescription &description = body.description();
    const auto            &fe          = body.dof_handler().get_fe();
    const ReferenceCell    reference   = cell->reference_cell();
    const unsigned int     n_q         = points.size();

    std::vector<LiftedFace> faces;
    for (const unsigned int f : cell->face_indices())
      {
        if (!cell->face(f)->at_boundary())
          continue;
        LiftedFace                         face;
        std::array<const Function<2> *, 2> data = {{nullptr, nullptr}};
        for (const auto &condition : description.dirichlet)
          if (condition.boundary_id == cell->face(f)->boundary_id())
            for (unsigned int c = 0; c < 2; ++c)
              if (condition.components[c])
                {
                  face.components[c] = true;
                  data[c]            = condition.displacement.get();
                }
        if (!face.components[0] && !face.components[1])
          continue;
        face.a             = reference.face_to_cell_vertices(f, 0, 1);
        face.b             = reference.face_to_cell_vertices(f, 1, 1);
        const Point<2> V_a = reference.vertex<2>(face.a);
        const Point<2> V_b = reference.vertex<2>(face.b);
        // The face's point at t = N_b of each point, where d = u_D - u_c
        // and its derivative along the face are taken.
        std::vector<Point<2>> face_points(n_q);
        std::vector<double>   t(n_q);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            t[q] = reference.d_linear_shape_function(points[q], face.b);
            face_points[q] = Point<2>((1 - t[q]) * V_a + t[q] * V_b);
          }
        FEValues<2> face_values(body.mapping(),
                                fe,
                                Quadrature<2>(face_points),
                                update_values | update_gradients |
                                  update_quadrature_points | update_jacobians);
        face_values.reinit(cell);
        std::vector<Vector<double>>            u_c(n_q, Vector<double>(2));
        std::vector<std::vector<Tensor<1, 2>>> grad_u_c(
          n_q, std::vector<Tensor<1, 2>>(2));
        face_values.get_function_values(u_kinematic, u_c);
        face_values.get_function_gradients(u_kinematic, grad_u_c);
        for (unsigned int c = 0; c < 2; ++c)
          if (face.components[c])
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const Point<2> &x = face_values.quadrature_point(q);
                // dx/dt = J (V_b - V_a).
                const Tensor<1, 2> tangent =
                  apply_transformation(face_values.jacobian(q), V_b - V_a);
                const double d = data[c]->value(x, c) - u_c[q](c);
                const double d_prime =
                  (data[c]->gradient(x, c) - grad_u_c[q][c]) * tangent;
                const double w = t[q] * (1 - t[q]);
                face.g[c].push_back(d / w);
                face.dg[c].push_back(d_prime / w -
                                     d * (1 - 2 * t[q]) / (w * w));
              }
        faces.push_back(face);
      }
    if (faces.empty())
      return result;

    FEValues<2> cell_values(body.mapping(),
                            fe,
                            Quadrature<2>(points),
                            update_inverse_jacobians);
    cell_values.reinit(cell);
    result.resize(n_q);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<2> &xi = points[q];
        // The reference gradient of r's two components.
        std::array<Tensor<1, 2>, 2> gradient;
        for (const auto &face : faces)
          {
            const double N_a = reference.d_linear_shape_function(xi, face.a);
            const double N_b = reference.d_linear_shape_function(xi, face.b);
            const Tensor<1, 2> grad_a =
              reference.d_linear_shape_function_gradient(xi, face.a);
            const Tensor<1, 2> grad_b =
              reference.d_linear_shape_function_gradient(xi, face.b);
            for (unsigned int c = 0; c < 2; ++c)
              if (face.components[c])
                gradient[c] += face.g[c][q] * (N_b * grad_a + N_a * grad_b) +
                               N_a * N_b * face.dg[c][q] * grad_b;
          }
        // To the physical cell: d r / d x_i = sum_k d r / d xi_k
        // d xi_k / d x_i.
        const DerivativeForm<1, 2, 2> &inverse =
          cell_values.inverse_jacobian(q);
        for (unsigned int c = 0; c < 2; ++c)
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int k = 0; k < 2; ++k)
              result[q][c][i] += gradient[c][k] * inverse[k][i];
      }
    return result;
  }



  DirichletDataLift
  dirichlet_data_lift(const ElasticBody                   &body,
                      const TrilinosWrappers::MPI::Vector &u_kinematic)
  {
    DirichletDataLift lift;
    const auto       &tria = body.triangulation();
    lift.squared.reinit(tria.n_active_cells());
    const DirichletDataLiftField field(body, u_kinematic);
    if (!field.active())
      return lift;

    const auto        &fe = body.dof_handler().get_fe();
    const unsigned int p  = fe.degree;
    // r is not a polynomial (g is d's own quotient); the rules below
    // integrate its polynomial part, degree p + 2 on triangles and per
    // direction on quadrilaterals, exactly. QGaussSimplex offers at most 4
    // points per direction (degree 7) in deal.II 9.4.
    const Quadrature<2> cell_rule =
      body.is_simplex_mesh() ?
        Quadrature<2>(QGaussSimplex<2>(std::min(p + 2, 4u))) :
        Quadrature<2>(QGauss<2>(p + 4));
    FEValues<2> cell_values(body.mapping(), fe, cell_rule, update_JxW_values);
    const ElasticMaterial &material = body.material();
    for (const auto &cell : body.dof_handler().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const auto gradients = field.gradients(cell, cell_rule.get_points());
        if (gradients.empty())
          continue;
        cell_values.reinit(cell);
        double energy = 0;
        for (const unsigned int q : cell_values.quadrature_point_indices())
          {
            const SymmetricTensor<2, 2> strain = symmetrize(gradients[q]);
            energy += material.stress(strain) * strain * cell_values.JxW(q);
          }
        lift.squared(cell->active_cell_index()) = energy;
      }
    lift.norm_squared =
      Utilities::MPI::sum(lift.squared.l1_norm(), tria.get_communicator());
    return lift;
  }
} // namespace coulomb_adapt
