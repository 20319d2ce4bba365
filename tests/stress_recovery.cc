// Stress recovery of the error indicator, ZZ1 (global L2 projection) and
// SPR (superconvergent patch recovery), on one body whose displacement is
// set by interpolation rather than solved for:
//  1. exactness. (a) A displacement of degree p + 1 on a parallelogram
//     mesh: its interpolant's stress is exact at the Gauss points of order
//     p, so SPR must return the exact stress (degree p) to round-off.
//     (b) A displacement of degree p, inside the FE space, on distorted
//     quadrilaterals with hanging nodes and on distorted triangles: its
//     stress lies in the recovered space and both methods must keep it;
//     also on meshes without an interior vertex (SPR's fallback fits).
//     (c) For information: (a)'s field on the distorted meshes, where the
//     Gauss points are not superconvergent and SPR is not exact.
//  2. convergence, for a smooth field under uniform refinement: the
//     recovered stress must converge faster than the raw FE stress.
// First, the raw stress at the quadrature points (QuadratureStress: what
// ZZ integrates and the volume terms read) is checked against deal.II's
// FEValues of the displacement's FESystem, and the recovered stress at
// those points (RecoveredStress::get_quadrature_values) against FEValues
// of the stress space; the ZZ mass operator against the assembled mass
// matrix; SPR's samples (stress and position at the Gauss points of order
// p) against FEValues.
// The output is the same on any number of ranks.

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/element_mass_operator.h>
#include <coulomb_adapt/indicator/quadrature_stress.h>
#include <coulomb_adapt/indicator/recovered_stress.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include "test_utilities.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <utility>

using namespace coulomb_adapt;

// u_c = sum over i + j <= n of a_cij x^i y^j, with fixed coefficients of
// size 1e-3 (stresses of order 1 for E = 1000).
class PolynomialDisplacement : public Function<2>
{
public:
  explicit PolynomialDisplacement(const unsigned int degree)
    : Function<2>(2)
    , degree(degree)
  {}

  double
  value(const Point<2> &p, const unsigned int c) const override
  {
    double u = 0;
    for (unsigned int i = 0; i <= degree; ++i)
      for (unsigned int j = 0; i + j <= degree; ++j)
        u += coefficient(c, i, j) * std::pow(p[0], i) * std::pow(p[1], j);
    return u;
  }

  Tensor<1, 2>
  gradient(const Point<2> &p, const unsigned int c) const override
  {
    Tensor<1, 2> g;
    for (unsigned int i = 0; i <= degree; ++i)
      for (unsigned int j = 0; i + j <= degree; ++j)
        {
          const double a = coefficient(c, i, j);
          if (i > 0)
            g[0] += a * i * std::pow(p[0], i - 1) * std::pow(p[1], j);
          if (j > 0)
            g[1] += a * j * std::pow(p[0], i) * std::pow(p[1], j - 1);
        }
    return g;
  }

private:
  static double
  coefficient(const unsigned int c, const unsigned int i, const unsigned int j)
  {
    return 1e-3 * std::sin(1. + 3. * c + 5. * i + 7. * j);
  }

  unsigned int degree;
};

// A smooth field that no polynomial space contains.
class SmoothDisplacement : public Function<2>
{
public:
  SmoothDisplacement()
    : Function<2>(2)
  {}

  double
  value(const Point<2> &p, const unsigned int c) const override
  {
    return c == 0 ? 1e-3 * std::sin(2. * p[0] + p[1]) :
                    1e-3 * std::cos(p[0] - 1.5 * p[1]);
  }

  Tensor<1, 2>
  gradient(const Point<2> &p, const unsigned int c) const override
  {
    if (c == 0)
      return 1e-3 * std::cos(2. * p[0] + p[1]) * Tensor<1, 2>({2., 1.});
    return -1e-3 * std::sin(p[0] - 1.5 * p[1]) * Tensor<1, 2>({1., -1.5});
  }
};

// One body on a given mesh. No boundary conditions: the displacement is
// interpolated, and Dirichlet constraints would overwrite it.
class RecoveryScene : public Scene
{
public:
  RecoveryScene(std::function<void(Triangulation<2> &)> make_mesh,
                std::function<void(Triangulation<2> &)> refine_locally = {})
    : make_mesh(make_mesh)
    , refine_locally(refine_locally)
  {}
  std::string
  name() const override
  {
    return "stress recovery";
  }
  void
  create_coarse_mesh(const unsigned int,
                     const CellType,
                     Triangulation<2> &tria) const override
  {
    make_mesh(tria);
  }
  void
  refine_initial_mesh(const unsigned int, Triangulation<2> &tria) const override
  {
    if (refine_locally)
      refine_locally(tria);
  }
  BodyDescription
  describe_body(const unsigned int) const override
  {
    BodyDescription d;
    d.name     = "body";
    d.material = {1000., 0.3};
    return d;
  }

private:
  std::function<void(Triangulation<2> &)> make_mesh;
  std::function<void(Triangulation<2> &)> refine_locally;
};

// [0, 2] x [0, 1.5] in 4 x 3 quadrilaterals (or 8 triangles each).
void
make_box(Triangulation<2> &tria, const CellType cell_type)
{
  make_rectangle(
    tria, Point<2>(0, 0), Point<2>(2, 1.5), {4, 3}, {{0, 0, 0, 0}}, cell_type);
}

const RecoveryScene parallelograms([](Triangulation<2> &tria) {
  make_box(tria, CellType::quadrilateral);
  GridTools::transform(
    [](const Point<2> &p) {
      return Point<2>(p[0] + 0.4 * p[1], 0.2 * p[0] + p[1]);
    },
    tria);
});

const RecoveryScene distorted_quadrilaterals([](Triangulation<2> &tria) {
  make_box(tria, CellType::quadrilateral);
  GridTools::distort_random(0.25, tria, true, 42);
});

// Two levels of hanging nodes: the left half refined once, cells near the
// bottom left corner once more.
const RecoveryScene distorted_quadrilaterals_with_hanging_nodes(
  [](Triangulation<2> &tria) {
    make_box(tria, CellType::quadrilateral);
    GridTools::distort_random(0.25, tria, true, 42);
  },
  [](Triangulation<2> &tria) {
    for (const double radius : {1.0, 0.5})
      {
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned() && cell->center()[0] < radius)
            cell->set_refine_flag();
        tria.execute_coarsening_and_refinement();
      }
  });

// No interior vertex at all: every node takes a fallback fit.
const RecoveryScene one_quadrilateral([](Triangulation<2> &tria) {
  GridGenerator::general_cell(tria,
                              std::vector<Point<2>>{Point<2>(0, 0),
                                                    Point<2>(1.2, 0.1),
                                                    Point<2>(-0.1, 0.9),
                                                    Point<2>(1.0, 1.3)});
});

const RecoveryScene two_triangles([](Triangulation<2> &tria) {
  GridGenerator::subdivided_hyper_rectangle_with_simplices(tria,
                                                           {1, 1},
                                                           Point<2>(0, 0),
                                                           Point<2>(1.2, 0.9));
});

const RecoveryScene distorted_triangles([](Triangulation<2> &tria) {
  make_box(tria, CellType::triangle);
  GridTools::distort_random(0.25, tria, true, 42);
});



// Errors of the raw stress K eps(u_h) and of the recovered stress against
// the exact stress, in the energy norm of the stress (K^-1), over all ranks.
struct StressErrors
{
  double raw;
  double recovered;
  double exact_norm;
};

StressErrors
compute_stress_errors(const ElasticBody     &body,
                      const RecoveredStress &recovery,
                      const Function<2>     &exact)
{
  const unsigned int  p = body.dof_handler().get_fe().degree;
  const Quadrature<2> quadrature =
    body.is_simplex_mesh() ?
      static_cast<Quadrature<2>>(QGaussSimplex<2>(p + 2)) :
      static_cast<Quadrature<2>>(QGauss<2>(p + 2));
  FEValues<2>                        displacement_values(body.mapping(),
                                  body.dof_handler().get_fe(),
                                  quadrature,
                                  update_gradients | update_quadrature_points |
                                    update_JxW_values);
  FEValues<2>                        recovered_values(body.mapping(),
                               recovery.dof_handler().get_fe(),
                               quadrature,
                               update_values);
  std::vector<SymmetricTensor<2, 2>> strains(quadrature.size());
  std::array<std::vector<double>, 3> recovered;
  for (auto &r : recovered)
    r.resize(quadrature.size());
  const auto energy = [&](const SymmetricTensor<2, 2> &sigma) {
    return sigma * body.material().strain(sigma);
  };

  double raw = 0, recovered_error = 0, norm = 0;
  for (const auto &cell : body.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        displacement_values.reinit(cell);
        recovered_values.reinit(
          DoFHandler<2>::active_cell_iterator(&body.triangulation(),
                                              cell->level(),
                                              cell->index(),
                                              &recovery.dof_handler()));
        displacement_values[FEValuesExtractors::Vector(0)]
          .get_function_symmetric_gradients(body.solution(), strains);
        for (unsigned int c = 0; c < 3; ++c)
          recovered_values.get_function_values(recovery.component(c),
                                               recovered[c]);
        for (const unsigned int q :
             displacement_values.quadrature_point_indices())
          {
            const Point<2> &x = displacement_values.quadrature_point(q);
            Tensor<2, 2>    gradient;
            for (unsigned int c = 0; c < 2; ++c)
              gradient[c] = exact.gradient(x, c);
            const SymmetricTensor<2, 2> sigma =
              body.material().stress(symmetrize(gradient));
            const SymmetricTensor<2, 2> sigma_h =
              body.material().stress(strains[q]);
            const SymmetricTensor<2, 2> sigma_r = stress_tensor(Tensor<1, 3>(
              {recovered[0][q], recovered[1][q], recovered[2][q]}));
            const double                JxW     = displacement_values.JxW(q);
            raw += energy(sigma_h - sigma) * JxW;
            recovered_error += energy(sigma_r - sigma) * JxW;
            norm += energy(sigma) * JxW;
          }
      }
  const MPI_Comm comm = body.triangulation().get_communicator();
  return {std::sqrt(Utilities::MPI::sum(raw, comm)),
          std::sqrt(Utilities::MPI::sum(recovered_error, comm)),
          std::sqrt(Utilities::MPI::sum(norm, comm))};
}

void
interpolate_displacement(ElasticBody &body, const Function<2> &u)
{
  TrilinosWrappers::MPI::Vector owned(body.locally_owned_dof_set(),
                                      body.triangulation().get_communicator());
  VectorTools::interpolate(body.mapping(), body.dof_handler(), u, owned);
  body.set_solution(owned);
}

// One body on @p scene's (unrefined) mesh, of degree @p degree, whose
// solution is the interpolant of @p u.
std::unique_ptr<ElasticBody>
interpolated_body(const RecoveryScene &scene,
                  const unsigned int   degree,
                  const Function<2>   &u)
{
  auto body = std::make_unique<ElasticBody>(
    MPI_COMM_WORLD,
    scene,
    0,
    CellType::quadrilateral,
    0,
    parameters::FiniteElements{degree, PlaneModel::plane_strain});
  body->setup_system();
  interpolate_displacement(*body, u);
  return body;
}

// The reference for QuadratureStress: sigma_c = K eps(u_h) from deal.II's
// FEValues of the displacement's FESystem (update_gradients), reinit'ed on
// @p cell here, at each of its points.
std::vector<Tensor<1, 3>>
reference_stresses(const ElasticBody                         &body,
                   FEValues<2>                               &reference,
                   const DoFHandler<2>::active_cell_iterator &cell)
{
  reference.reinit(cell);
  std::vector<SymmetricTensor<2, 2>> strains(reference.n_quadrature_points);
  reference[FEValuesExtractors::Vector(0)].get_function_symmetric_gradients(
    body.solution(), strains);
  std::vector<Tensor<1, 3>> stresses;
  for (const auto &strain : strains)
    stresses.push_back(stress_components(body.material().stress(strain)));
  return stresses;
}

// QuadratureStress (strain from the scalar base element's gradients and
// the nodal values) against deal.II's FEValues of the displacement's
// FESystem at the same points: stresses and each weight must agree to
// round-off, cell by cell, on hanging-node and triangle meshes, p = 1 and
// 2. Then the ZZ-recovered stress at these points from the reference
// shape-value table (get_quadrature_values) against FEValues of the
// stress space.
void
check_quadrature_stress(const std::string &label, const ElasticBody &body)
{
  const unsigned int     degree = body.dof_handler().get_fe().degree;
  const QuadratureStress raw_stress(body, body.solution());

  FEValues<2>     reference(body.mapping(),
                        body.dof_handler().get_fe(),
                        body.cell_quadrature(),
                        update_gradients | update_JxW_values);
  RecoveredStress recovered(body);
  recovered.recover(raw_stress, StressRecoveryMethod::l2_projection);
  FEValues<2>                        recovered_reference(body.mapping(),
                                  recovered.dof_handler().get_fe(),
                                  body.cell_quadrature(),
                                  update_values);
  const unsigned int                 n_points = body.cell_quadrature().size();
  std::vector<Tensor<1, 3>>          recovered_values(n_points);
  std::array<std::vector<double>, 3> reference_components;
  for (auto &r : reference_components)
    r.resize(n_points);
  double       largest_stress = 0, stress_difference = 0;
  double       weight_difference = 0, recovered_difference = 0;
  unsigned int owned_cell = 0;
  for (const auto &cell : body.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        const DoFHandler<2>::active_cell_iterator stress_cell(
          &body.triangulation(),
          cell->level(),
          cell->index(),
          &recovered.dof_handler());
        recovered.get_quadrature_values(stress_cell, recovered_values);
        recovered_reference.reinit(stress_cell);
        for (unsigned int c = 0; c < 3; ++c)
          recovered_reference.get_function_values(recovered.component(c),
                                                  reference_components[c]);
        const auto sigmas = reference_stresses(body, reference, cell);
        for (const unsigned int q : reference.quadrature_point_indices())
          {
            const Tensor<1, 3> &sigma = sigmas[q];
            largest_stress            = std::max(largest_stress, sigma.norm());
            stress_difference =
              std::max(stress_difference,
                       (raw_stress.stress(owned_cell, q) - sigma).norm());
            weight_difference =
              std::max(weight_difference,
                       std::abs(raw_stress.JxW(owned_cell, q) -
                                reference.JxW(q)) /
                         reference.JxW(q));
            for (unsigned int c = 0; c < 3; ++c)
              recovered_difference =
                std::max(recovered_difference,
                         std::abs(recovered_values[q][c] -
                                  reference_components[c][q]));
          }
        ++owned_cell;
      }
  const MPI_Comm comm  = body.triangulation().get_communicator();
  largest_stress       = Utilities::MPI::max(largest_stress, comm);
  stress_difference    = Utilities::MPI::max(stress_difference, comm);
  weight_difference    = Utilities::MPI::max(weight_difference, comm);
  recovered_difference = Utilities::MPI::max(recovered_difference, comm);
  const bool same      = stress_difference <= 1e-13 * largest_stress &&
                    weight_difference <= 1e-14 &&
                    recovered_difference <= 1e-13 * largest_stress;
  testing::root_output()
    << "raw and recovered stress at the quadrature points, " << label << ", "
    << (body.is_simplex_mesh() ? "P" : "Q") << degree
    << ": same as FEValues: " << (same ? "yes" : "no") << std::endl;
  AssertThrow(same,
              ExcMessage(label + ": differences from FEValues: raw stress " +
                         std::to_string(stress_difference) + ", JxW " +
                         std::to_string(weight_difference) +
                         " (relative), recovered stress " +
                         std::to_string(recovered_difference)));
}

// SPR's samples: QuadratureStress at the Gauss points of order p, with the
// points' positions, against deal.II's FEValues of the displacement's
// FESystem at the same points (stresses and positions to round-off).
void
check_sampled_stress(const std::string &label, const ElasticBody &body)
{
  const unsigned int  degree = body.dof_handler().get_fe().degree;
  const Quadrature<2> sampling =
    body.is_simplex_mesh() ?
      static_cast<Quadrature<2>>(QGaussSimplex<2>(degree)) :
      static_cast<Quadrature<2>>(QGauss<2>(degree));
  const QuadratureStress sampled(body, body.solution(), sampling, true);
  FEValues<2>            reference(body.mapping(),
                        body.dof_handler().get_fe(),
                        sampling,
                        update_gradients | update_quadrature_points);
  double                 largest_stress = 0, stress_difference = 0;
  double                 largest_coordinate = 0, point_difference = 0;
  unsigned int           owned_cell = 0;
  for (const auto &cell : body.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        const auto sigmas = reference_stresses(body, reference, cell);
        for (const unsigned int q : reference.quadrature_point_indices())
          {
            const Tensor<1, 3> &sigma = sigmas[q];
            largest_stress            = std::max(largest_stress, sigma.norm());
            stress_difference =
              std::max(stress_difference,
                       (sampled.stress(owned_cell, q) - sigma).norm());
            largest_coordinate = std::max(largest_coordinate,
                                          reference.quadrature_point(q).norm());
            point_difference =
              std::max(point_difference,
                       sampled.point(owned_cell, q)
                         .distance(reference.quadrature_point(q)));
          }
        ++owned_cell;
      }
  const MPI_Comm comm = body.triangulation().get_communicator();
  largest_stress      = Utilities::MPI::max(largest_stress, comm);
  stress_difference   = Utilities::MPI::max(stress_difference, comm);
  largest_coordinate  = Utilities::MPI::max(largest_coordinate, comm);
  point_difference    = Utilities::MPI::max(point_difference, comm);
  const bool same     = owned_cell == sampled.n_cells() &&
                    stress_difference <= 1e-13 * largest_stress &&
                    point_difference <= 1e-14 * largest_coordinate;
  testing::root_output() << "SPR samples (Gauss points of order p), " << label
                         << ", " << (body.is_simplex_mesh() ? "P" : "Q")
                         << degree
                         << ": same as FEValues: " << (same ? "yes" : "no")
                         << std::endl;
  AssertThrow(same,
              ExcMessage(label +
                         ": SPR samples differ from FEValues: "
                         "stress " +
                         std::to_string(stress_difference) + ", position " +
                         std::to_string(point_difference)));
}

// The ZZ mass system's operator (element matrices from QuadratureStress's
// weights and the reference shape values, hanging nodes resolved in each
// product) against the mass matrix that deal.II's FEValues assembles
// through AffineConstraints: A x = C^T M C x on the unconstrained DoFs to
// round-off, the identity on the constrained ones, and the Jacobi
// preconditioner 1 / diag(C^T M C), for three different vectors at once.
void
check_mass_operator(const std::string &label, const ElasticBody &body)
{
  const unsigned int     degree = body.dof_handler().get_fe().degree;
  const QuadratureStress raw_stress(body, body.solution());
  const MPI_Comm         comm = body.triangulation().get_communicator();

  const FiniteElement<2> &fe = body.dof_handler().get_fe().base_element(0);
  DoFHandler<2>           dofs(body.triangulation());
  dofs.distribute_dofs(fe);
  const IndexSet owned = dofs.locally_owned_dofs();
  IndexSet       relevant;
  DoFTools::extract_locally_relevant_dofs(dofs, relevant);
  AffineConstraints<double> constraints(relevant);
  DoFTools::make_hanging_node_constraints(dofs, constraints);
  constraints.close();

  const Quadrature<2> &quadrature = body.cell_quadrature();
  FullMatrix<double>   shape_values(fe.n_dofs_per_cell(), quadrature.size());
  for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      shape_values(k, q) = fe.shape_value(k, quadrature.point(q));
  const auto partitioner =
    std::make_shared<Utilities::MPI::Partitioner>(owned, relevant, comm);
  const ElementMassOperator mass(
    dofs, constraints, partitioner, shape_values, raw_stress);

  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  TrilinosWrappers::SparseMatrix reference;
  reference.reinit(owned, owned, dsp, comm);
  FEValues<2>        fe_values(body.mapping(),
                        fe,
                        quadrature,
                        update_values | update_JxW_values);
  FullMatrix<double> cell_matrix(fe.n_dofs_per_cell(), fe.n_dofs_per_cell());
  std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        cell_matrix = 0;
        for (const unsigned int q : fe_values.quadrature_point_indices())
          for (const unsigned int i : fe_values.dof_indices())
            for (const unsigned int j : fe_values.dof_indices())
              cell_matrix(i, j) += fe_values.shape_value(i, q) *
                                   fe_values.shape_value(j, q) *
                                   fe_values.JxW(q);
        cell->get_dof_indices(dof_indices);
        constraints.distribute_local_to_global(cell_matrix,
                                               dof_indices,
                                               reference);
      }
  reference.compress(VectorOperation::add);

  ElementMassOperator::BlockVectorType x, y, ones, inverse_diagonal;
  for (auto *v : {&x, &y, &ones, &inverse_diagonal})
    mass.initialize_dof_vector(*v);
  // x is nonzero on the constrained DoFs too: the operator must return it
  // there (identity) and ignore it elsewhere, as the assembled matrix does
  // (its constrained columns are zero).
  for (const types::global_dof_index i : owned)
    for (unsigned int b = 0; b < ElementMassOperator::n_blocks; ++b)
      {
        ones.block(b)(i) = 1;
        x.block(b)(i)    = std::sin(1. + 0.7 * i + 2. * b);
      }
  mass.vmult(y, x);
  // CG hands its operator vectors without ghost values and expects them
  // back so.
  AssertThrow(!x.has_ghost_elements(),
              ExcMessage("vmult left its source vector ghosted"));
  mass.precondition_Jacobi(inverse_diagonal, ones, 1.);

  double largest = 0, product_difference = 0, diagonal_difference = 0;
  bool   identity_on_constrained = true;
  for (unsigned int b = 0; b < ElementMassOperator::n_blocks; ++b)
    {
      TrilinosWrappers::MPI::Vector x_reference(owned, comm);
      TrilinosWrappers::MPI::Vector y_reference(owned, comm);
      for (const types::global_dof_index i : owned)
        x_reference(i) = x.block(b)(i);
      x_reference.compress(VectorOperation::insert);
      reference.vmult(y_reference, x_reference);
      for (const types::global_dof_index i : owned)
        if (constraints.is_constrained(i))
          identity_on_constrained = identity_on_constrained &&
                                    y.block(b)(i) == x.block(b)(i) &&
                                    inverse_diagonal.block(b)(i) == 1.;
        else
          {
            largest = std::max(largest, std::abs(y_reference(i)));
            product_difference =
              std::max(product_difference,
                       std::abs(y.block(b)(i) - y_reference(i)));
            diagonal_difference =
              std::max(diagonal_difference,
                       std::abs(inverse_diagonal.block(b)(i) *
                                  reference.diag_element(i) -
                                1.));
          }
    }
  largest             = Utilities::MPI::max(largest, comm);
  product_difference  = Utilities::MPI::max(product_difference, comm);
  diagonal_difference = Utilities::MPI::max(diagonal_difference, comm);
  identity_on_constrained =
    Utilities::MPI::min(identity_on_constrained ? 1 : 0, comm) == 1;
  const bool same = product_difference <= 1e-13 * largest &&
                    diagonal_difference <= 1e-13 && identity_on_constrained;
  testing::root_output() << "ZZ mass operator, " << label << ", "
                         << (body.is_simplex_mesh() ? "P" : "Q") << degree
                         << ": same as the assembled C^T M C: "
                         << (same ? "yes" : "no") << std::endl;
  AssertThrow(same,
              ExcMessage(label +
                         ": mass operator differs from the assembled "
                         "matrix: product " +
                         std::to_string(product_difference / largest) +
                         " (relative), diagonal " +
                         std::to_string(diagonal_difference) +
                         " (relative), identity on constrained DoFs " +
                         (identity_on_constrained ? "yes" : "no")));
}

const std::vector<StressRecoveryMethod> methods =
  {StressRecoveryMethod::l2_projection, StressRecoveryMethod::spr};

std::string
element_name(const ElasticBody &body)
{
  return (body.is_simplex_mesh() ? "P" : "Q") +
         std::to_string(body.dof_handler().get_fe().degree);
}

// Relative recovered-stress error of @p u for each method; those in
// @p must_be_exact must vanish to round-off.
void
check_exactness(const std::string                      &label,
                const RecoveryScene                    &scene,
                const unsigned int                      degree,
                const Function<2>                      &u,
                const std::vector<StressRecoveryMethod> must_be_exact)
{
  const double tolerance = 1e-10;
  auto         out       = testing::root_output();

  const auto             body_pointer = interpolated_body(scene, degree, u);
  const ElasticBody     &body         = *body_pointer;
  RecoveredStress        recovery(body);
  const QuadratureStress raw_stress(body, body.solution());

  out << label << ", " << element_name(body) << ", cells "
      << body.triangulation().n_global_active_cells() << ":";
  for (const auto method : methods)
    {
      recovery.recover(raw_stress, method);
      const StressErrors e        = compute_stress_errors(body, recovery, u);
      const double       relative = e.recovered / e.exact_norm;
      const bool         exact =
        std::find(must_be_exact.begin(), must_be_exact.end(), method) !=
        must_be_exact.end();
      out << "  " << to_string(method) << " ";
      if (relative < tolerance)
        out << "exact";
      else
        out << std::scientific << std::setprecision(2) << relative
            << std::defaultfloat;
      AssertThrow(!exact || relative < tolerance,
                  ExcMessage(label + ", " + to_string(method) +
                             ": relative stress error " +
                             std::to_string(relative) + " is not round-off"));
    }
  out << std::endl;
}

// What a recovery gains over the raw stress on the finest meshes: in
// convergence rate, and as the factor raw error / recovered error.
struct Gain
{
  double rate;
  double factor;
};

// Relative errors of the raw and recovered stresses of the smooth field
// under uniform refinement, and their rates; the gains of ZZ1 and SPR on
// the last two meshes must be at least @p zz_gain and @p spr_gain.
void
check_convergence(const std::string   &label,
                  const RecoveryScene &scene,
                  const unsigned int   degree,
                  const unsigned int   n_cycles,
                  const Gain          &zz_gain,
                  const Gain          &spr_gain)
{
  const SmoothDisplacement                   u;
  auto                                       out = testing::root_output();
  ElasticBody                                body(MPI_COMM_WORLD,
                   scene,
                   0,
                   CellType::quadrilateral,
                   1,
                   {degree, PlaneModel::plane_strain});
  ConvergenceTable                           table;
  std::map<std::string, std::vector<double>> errors;
  for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
    {
      if (cycle > 0)
        body.refine_uniformly();
      body.setup_system();
      interpolate_displacement(body, u);
      RecoveredStress        recovery(body);
      const QuadratureStress raw_stress(body, body.solution());
      table.add_value("cells", body.triangulation().n_global_active_cells());
      for (const auto method : methods)
        {
          recovery.recover(raw_stress, method);
          const StressErrors e = compute_stress_errors(body, recovery, u);
          if (method == methods.front())
            {
              errors["raw"].push_back(e.raw / e.exact_norm);
              table.add_value("raw", e.raw / e.exact_norm);
            }
          errors[to_string(method)].push_back(e.recovered / e.exact_norm);
          table.add_value(to_string(method), e.recovered / e.exact_norm);
        }
    }
  for (const std::string column : {"raw", "zz", "spr"})
    {
      table.set_scientific(column, true);
      table.set_precision(column, 3);
      // h halves from one row to the next.
      table.evaluate_convergence_rates(column,
                                       ConvergenceTable::reduction_rate_log2);
    }
  out << label << ", " << element_name(body)
      << ": relative stress errors (energy norm)" << std::endl;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    table.write_text(std::cout);
  out << std::endl;

  const auto rate = [&](const std::string &column) {
    const auto &e = errors[column];
    return std::log2(e[e.size() - 2] / e.back());
  };
  AssertThrow(std::abs(rate("raw") - degree) < 0.1,
              ExcMessage(label + ": raw stress rate " +
                         std::to_string(rate("raw")) + " != p"));
  for (const auto &[method, gain] :
       {std::make_pair("zz", zz_gain), std::make_pair("spr", spr_gain)})
    {
      const double factor = errors["raw"].back() / errors[method].back();
      AssertThrow(rate(method) > rate("raw") + gain.rate,
                  ExcMessage(label + ", " + method + ": rate " +
                             std::to_string(rate(method)) + " is not " +
                             std::to_string(gain.rate) +
                             " above the raw rate " +
                             std::to_string(rate("raw"))));
      AssertThrow(factor > gain.factor,
                  ExcMessage(label + ", " + method + ": recovered error only " +
                             std::to_string(factor) + " times below raw"));
    }
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const auto                       spr = StressRecoveryMethod::spr;
  const auto                       zz  = StressRecoveryMethod::l2_projection;

  const SmoothDisplacement smooth;
  const std::vector<std::pair<std::string, const RecoveryScene *>>
    checked_meshes = {{"distorted quadrilaterals with hanging nodes",
                       &distorted_quadrilaterals_with_hanging_nodes},
                      {"distorted triangles", &distorted_triangles}};
  for (const unsigned int p : {1u, 2u})
    for (const auto &[label, scene] : checked_meshes)
      {
        const auto body = interpolated_body(*scene, p, smooth);
        check_quadrature_stress(label, *body);
        check_mass_operator(label, *body);
        check_sampled_stress(label, *body);
      }
  testing::root_output() << std::endl;

  for (const unsigned int p : {1u, 2u})
    {
      const PolynomialDisplacement higher(p + 1), in_space(p);
      check_exactness(
        "(a) degree p+1 on parallelograms", parallelograms, p, higher, {spr});
      check_exactness("(b) degree p on distorted quadrilaterals with "
                      "hanging nodes",
                      distorted_quadrilaterals_with_hanging_nodes,
                      p,
                      in_space,
                      {zz, spr});
      check_exactness("(b) degree p on distorted triangles",
                      distorted_triangles,
                      p,
                      in_space,
                      {zz, spr});
      check_exactness("(b) degree p on one quadrilateral",
                      one_quadrilateral,
                      p,
                      in_space,
                      {zz, spr});
      check_exactness(
        "(b) degree p on two triangles", two_triangles, p, in_space, {zz, spr});
      check_exactness("(c) degree p+1 on distorted quadrilaterals",
                      distorted_quadrilaterals,
                      p,
                      higher,
                      {});
      check_exactness("(c) degree p+1 on distorted triangles",
                      distorted_triangles,
                      p,
                      higher,
                      {});
    }
  testing::root_output() << std::endl;

  // Q_p: the Gauss points of order p are superconvergent on the cells of
  // a uniformly refined mesh (parallelograms up to O(h^2)): SPR gains one
  // order. ZZ1 gains half an order for p = 1 (its error concentrates
  // along the boundary) and, for p = 2, only a little in the constant.
  check_convergence("distorted quadrilaterals",
                    distorted_quadrilaterals,
                    1,
                    5,
                    {0.4, 10},
                    {0.9, 20});
  check_convergence("distorted quadrilaterals",
                    distorted_quadrilaterals,
                    2,
                    4,
                    {-0.1, 1},
                    {0.9, 20});
  // P_1: a centroid's gradient error is O(h); it cancels between the
  // point-symmetric triangles around a vertex of a refined coarse cell,
  // not along the lines of the coarse mesh, which leaves SPR at rate 1.5
  // (2 on translation-invariant meshes). P_2: the gradient errors at the
  // Gauss points of a triangle and of its mirror image are equal, not
  // opposite: SPR keeps rate p, with a much smaller constant.
  check_convergence(
    "distorted triangles", distorted_triangles, 1, 4, {0.4, 5}, {0.4, 10});
  check_convergence(
    "distorted triangles", distorted_triangles, 2, 3, {-0.1, 1}, {-0.1, 10});
}
