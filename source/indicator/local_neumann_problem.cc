#include <deal.II/base/quadrature_lib.h>

#include <coulomb_adapt/indicator/local_neumann_problem.h>

#include <algorithm>
#include <cmath>

namespace coulomb_adapt
{
  LocalNeumannProblem::LocalNeumannProblem(const ElasticBody &body,
                                           const unsigned int degree)
    : body(body)
    , degree(degree)
  {
    for (unsigned int total = 0; total <= degree; ++total)
      for (unsigned int b = 0; b <= total; ++b)
        exponents.push_back({{total - b, b}});
    cell_rule =
      body.is_simplex_mesh() ?
        // Witherden-Vincent: QGaussSimplex stops at 4 points per direction.
        std::unique_ptr<Quadrature<2>>(
          new QWitherdenVincentSimplex<2>(std::min(degree + 1, 7u))) :
        std::unique_ptr<Quadrature<2>>(new QGauss<2>(degree + 1));
    fe_values            = std::make_unique<FEValues<2>>(body.mapping(),
                                              body.dof_handler().get_fe(),
                                              *cell_rule,
                                              update_gradients |
                                                update_quadrature_points |
                                                update_JxW_values);
    const unsigned int M = exponents.size();
    gradients_at.assign(cell_rule->size(), std::vector<Tensor<1, 2>>(M));
    JxW.resize(cell_rule->size());
    sigma_c.resize(cell_rule->size());
    stiffness.reinit(2 * M, 2 * M);
    body_force.reinit(2 * M);
    sigma_c_work.reinit(2 * M);
    // The rigid motions' coefficients: the translations and the rotation
    // (-xi_y, xi_x); exponents (0,0), (1,0), (0,1) are the first three.
    for (auto &mode : rigid)
      mode.assign(2 * M, 0.);
    rigid[0][0]     = 1;
    rigid[1][M]     = 1;
    rigid[2][2]     = -1;
    rigid[2][M + 1] = 1;
  }



  unsigned int
  LocalNeumannProblem::n_coefficients() const
  {
    return 2 * exponents.size();
  }



  const Vector<double> &
  LocalNeumannProblem::body_force_load() const
  {
    return body_force;
  }



  void
  LocalNeumannProblem::evaluate(const Point<2> &x) const
  {
    const double xi[2] = {(x[0] - centre[0]) / h, (x[1] - centre[1]) / h};
    // Powers xi_d^0 ... xi_d^degree, by products (no std::pow).
    double power[2][16];
    for (unsigned int d = 0; d < 2; ++d)
      {
        power[d][0] = 1;
        for (unsigned int e = 1; e <= degree; ++e)
          power[d][e] = power[d][e - 1] * xi[d];
      }
    values.resize(exponents.size());
    gradients.resize(exponents.size());
    for (unsigned int m = 0; m < exponents.size(); ++m)
      {
        const auto &e = exponents[m];
        values[m]     = power[0][e[0]] * power[1][e[1]];
        gradients[m][0] =
          e[0] == 0 ? 0. : e[0] * power[0][e[0] - 1] * power[1][e[1]] / h;
        gradients[m][1] =
          e[1] == 0 ? 0. : e[1] * power[0][e[0]] * power[1][e[1] - 1] / h;
      }
  }



  void
  LocalNeumannProblem::reinit(const DoFHandler<2>::active_cell_iterator &cell,
                              const TrilinosWrappers::MPI::Vector &u_kinematic)
  {
    AssertThrow(degree < 16, ExcMessage("CRE local problems: degree < 16."));
    centre = cell->center();
    h      = cell->diameter();
    fe_values->reinit(cell);
    const FEValuesExtractors::Vector   displacement(0);
    std::vector<SymmetricTensor<2, 2>> strains(cell_rule->size());
    (*fe_values)[displacement].get_function_symmetric_gradients(u_kinematic,
                                                                strains);
    const ElasticMaterial &material    = body.material();
    const BodyDescription &description = body.description();
    const unsigned int     M           = exponents.size();

    // K from the Gram matrices G_de(m, n) = int d_d phi_m d_e phi_n of the
    // scalar monomials: with sigma = lambda tr(eps) I + 2 mu eps,
    //   K_(c,m)(c',n) = lambda G_cc' + mu (delta_cc' (G_00 + G_11) + G_c'c).
    FullMatrix<double> G[2][2];
    for (auto &row : G)
      for (auto &g : row)
        g.reinit(M, M);
    body_force   = 0;
    sigma_c_work = 0;
    for (const unsigned int q : fe_values->quadrature_point_indices())
      {
        const Point<2> &x = fe_values->quadrature_point(q);
        evaluate(x);
        gradients_at[q] = gradients;
        JxW[q]          = fe_values->JxW(q);
        sigma_c[q]      = material.stress(strains[q]);
        for (unsigned int m = 0; m < M; ++m)
          {
            const Tensor<1, 2> gm = gradients[m] * JxW[q];
            for (unsigned int n = 0; n < M; ++n)
              for (unsigned int d = 0; d < 2; ++d)
                for (unsigned int e = 0; e < 2; ++e)
                  G[d][e](m, n) += gm[d] * gradients[n][e];
            // sigma_c : eps(phi_m e_c) = (sigma_c grad phi_m)_c.
            const Tensor<1, 2> work = sigma_c[q] * gm;
            sigma_c_work(m) += work[0];
            sigma_c_work(M + m) += work[1];
          }
        if (description.body_force)
          {
            const Tensor<1, 2> f = description.body_force(x);
            for (unsigned int m = 0; m < M; ++m)
              {
                body_force(m) += f[0] * values[m] * JxW[q];
                body_force(M + m) += f[1] * values[m] * JxW[q];
              }
          }
      }
    const double lambda = material.lambda(), mu = material.mu();
    for (unsigned int c = 0; c < 2; ++c)
      for (unsigned int d = 0; d < 2; ++d)
        for (unsigned int m = 0; m < M; ++m)
          for (unsigned int n = 0; n < M; ++n)
            stiffness(c * M + m, d * M + n) =
              lambda * G[c][d](m, n) +
              mu *
                ((c == d ? G[0][0](m, n) + G[1][1](m, n) : 0.) + G[d][c](m, n));

    // K + s R R^T has, for a load orthogonal to R, the solution of K u =
    // load that is orthogonal to R; it is symmetric positive definite, so
    // one Cholesky factor serves every load of the cell.
    double scale = 0;
    for (unsigned int a = 0; a < 2 * M; ++a)
      scale = std::max(scale, stiffness(a, a));
    for (const auto &mode : rigid)
      for (unsigned int a = 0; a < 2 * M; ++a)
        for (unsigned int b = 0; b < 2 * M; ++b)
          stiffness(a, b) += scale * mode[a] * mode[b];
    factor.reinit(2 * M, 2 * M); // also resets its state after a factorisation
    factor = stiffness;
    factor.compute_cholesky_factorization();
  }



  const std::vector<double> &
  LocalNeumannProblem::monomial_values(const Point<2> &x) const
  {
    evaluate(x);
    return values;
  }



  void
  LocalNeumannProblem::add_traction(Vector<double>            &load,
                                    const Point<2>            &x,
                                    const Tensor<1, 2>        &t,
                                    const double               w,
                                    const std::array<bool, 2> &components) const
  {
    evaluate(x);
    const unsigned int M = exponents.size();
    for (unsigned int c = 0; c < 2; ++c)
      if (components[c])
        for (unsigned int m = 0; m < M; ++m)
          load(c * M + m) += t[c] * values[m] * w;
  }



  double
  LocalNeumannProblem::solve(const Vector<double> &load,
                             Vector<double>       &coefficients) const
  {
    double size = 0, rigid_load = 0;
    for (unsigned int a = 0; a < load.size(); ++a)
      size += std::abs(load(a));
    for (const auto &mode : rigid)
      {
        double w = 0;
        for (unsigned int a = 0; a < load.size(); ++a)
          w += mode[a] * load(a);
        rigid_load = std::max(rigid_load, std::abs(w));
      }
    coefficients = load;
    factor.solve(coefficients);
    return size > 0 ? rigid_load / size : 0.;
  }



  double
  LocalNeumannProblem::kinematic_work(const Vector<double> &v) const
  {
    return sigma_c_work * v;
  }



  std::array<double, 2>
  LocalNeumannProblem::errors(const Vector<double> &coefficients) const
  {
    const ElasticMaterial &material = body.material();
    const unsigned int     M        = exponents.size();
    std::array<double, 2>  result   = {{0., 0.}};
    for (unsigned int q = 0; q < JxW.size(); ++q)
      {
        Tensor<2, 2> grad_u;
        for (unsigned int m = 0; m < M; ++m)
          for (unsigned int c = 0; c < 2; ++c)
            grad_u[c] += coefficients(c * M + m) * gradients_at[q][m];
        const SymmetricTensor<2, 2> sigma_hat =
          material.stress(symmetrize(grad_u));
        const SymmetricTensor<2, 2> minus = sigma_hat - sigma_c[q];
        const SymmetricTensor<2, 2> plus  = sigma_hat + sigma_c[q];
        result[0] += minus * material.strain(minus) * JxW[q];
        result[1] += plus * material.strain(plus) * JxW[q];
      }
    return result;
  }
} // namespace coulomb_adapt
