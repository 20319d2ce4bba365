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
    // Triangles are affine: every integrand is a polynomial of degree at
    // most 2 (degree - 1) (stiffness, moments, errors), which
    // Witherden-Vincent with n points integrates exactly from n = degree
    // on (degree 2n - 1; QGaussSimplex stops at 4 points per direction).
    // On quadrilaterals the integrands are rational: one Gauss point more.
    cell_rule            = body.is_simplex_mesh() ?
                             std::unique_ptr<Quadrature<2>>(
                    new QWitherdenVincentSimplex<2>(std::min(degree, 7u))) :
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
    sigma_fe.resize(cell_rule->size());
    strains.resize(cell_rule->size());
    moment.reinit(2 * degree - 1, 2 * degree - 1);
    stiffness.reinit(2 * M, 2 * M);
    factor.reinit(2 * M, 2 * M);
    body_force.reinit(2 * M);
    sigma_c_work.reinit(2 * M);
    whitened_sigma_c_work.reinit(2 * M);
    sigma_fe_work.reinit(2 * M);
    whitened_sigma_fe_work.reinit(2 * M);
    forward_scratch.reinit(2 * M);
    // The rigid motions' coefficients: the translations and the rotation
    // (-xi_y, xi_x); exponents (0,0), (1,0), (0,1) are the first three.
    for (auto &mode : rigid)
      mode.assign(2 * M, 0.);
    rigid[0][0]     = 1;
    rigid[1][M]     = 1;
    rigid[2][2]     = -1;
    rigid[2][M + 1] = 1;
  }



  LocalNeumannProblem::LocalNeumannProblem(const LocalNeumannProblem &other)
    : LocalNeumannProblem(other.body, other.degree)
  {
    kinematic_lift = other.kinematic_lift;
  }



  void
  LocalNeumannProblem::set_kinematic_lift(const DirichletDataLiftField *lift)
  {
    kinematic_lift = lift;
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
  LocalNeumannProblem::evaluate(const Point<2> &x,
                                const bool      with_gradients) const
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
    for (unsigned int m = 0; m < exponents.size(); ++m)
      values[m] = power[0][exponents[m][0]] * power[1][exponents[m][1]];
    if (!with_gradients)
      return;
    gradients.resize(exponents.size());
    for (unsigned int m = 0; m < exponents.size(); ++m)
      {
        const auto &e = exponents[m];
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
    const FEValuesExtractors::Vector displacement(0);
    (*fe_values)[displacement].get_function_symmetric_gradients(u_kinematic,
                                                                strains);
    const ElasticMaterial &material = body.material();
    for (unsigned int q = 0; q < strains.size(); ++q)
      sigma_fe[q] = material.stress(strains[q]);
    if (kinematic_lift != nullptr)
      {
        const auto lift =
          kinematic_lift->gradients(cell, cell_rule->get_points());
        for (unsigned int q = 0; q < lift.size(); ++q)
          strains[q] += symmetrize(lift[q]);
      }
    const BodyDescription &description = body.description();
    const unsigned int     M           = exponents.size();
    const unsigned int     n_moments   = moment.size(0);

    // One pass over the quadrature points: the moments of the monomials,
    // the values the error needs (gradients, JxW, sigma_c), the work of
    // sigma_c and of the body force on each basis function.
    moment.fill(0.);
    body_force     = 0;
    sigma_c_work   = 0;
    sigma_c_energy = 0;
    sigma_fe_work  = 0;
    fe_energy      = 0;
    for (const unsigned int q : fe_values->quadrature_point_indices())
      {
        const Point<2> &x = fe_values->quadrature_point(q);
        evaluate(x);
        gradients_at[q] = gradients;
        JxW[q]          = fe_values->JxW(q);
        sigma_c[q]      = material.stress(strains[q]);
        sigma_c_energy += sigma_c[q] * strains[q] * JxW[q];
        const double xi[2] = {(x[0] - centre[0]) / h, (x[1] - centre[1]) / h};
        double       xi_power = JxW[q];
        for (unsigned int i = 0; i < n_moments; ++i, xi_power *= xi[0])
          {
            double power = xi_power;
            for (unsigned int j = 0; i + j < n_moments; ++j, power *= xi[1])
              moment(i, j) += power;
          }
        for (unsigned int m = 0; m < M; ++m)
          {
            // sigma_c : eps(phi_m e_c) = (sigma_c grad phi_m)_c.
            const Tensor<1, 2> work = sigma_c[q] * gradients[m];
            sigma_c_work(m) += work[0] * JxW[q];
            sigma_c_work(M + m) += work[1] * JxW[q];
          }
        if (kinematic_lift != nullptr)
          {
            fe_energy += sigma_fe[q] * material.strain(sigma_fe[q]) * JxW[q];
            const SymmetricTensor<2, 2> mean = (sigma_c[q] + sigma_fe[q]) / 2;
            for (unsigned int m = 0; m < M; ++m)
              {
                const Tensor<1, 2> work = mean * gradients[m];
                sigma_fe_work(m) += work[0] * JxW[q];
                sigma_fe_work(M + m) += work[1] * JxW[q];
              }
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
    assemble_stiffness();

    // K + s R R^T has, for a load orthogonal to R, the solution of K u =
    // load that is orthogonal to R; it is symmetric positive definite, so
    // one Cholesky factor serves every load of the cell. At 2 M <= 42
    // unknowns deal.II's FullMatrix loops beat a LAPACK call per load.
    double scale = 0;
    for (unsigned int a = 0; a < 2 * M; ++a)
      scale = std::max(scale, stiffness(a, a));
    for (const auto &mode : rigid)
      for (unsigned int a = 0; a < 2 * M; ++a)
        if (mode[a] != 0)
          for (unsigned int b = 0; b < 2 * M; ++b)
            stiffness(a, b) += scale * mode[a] * mode[b];
    factor.cholesky(stiffness);
    whiten(sigma_c_work, whitened_sigma_c_work);
    if (kinematic_lift != nullptr)
      whiten(sigma_fe_work, whitened_sigma_fe_work);
  }



  const Vector<double> &
  LocalNeumannProblem::whitened_normalisation_work() const
  {
    return kinematic_lift != nullptr ? whitened_sigma_fe_work :
                                       whitened_sigma_c_work;
  }



  double
  LocalNeumannProblem::normalisation_offset() const
  {
    return kinematic_lift != nullptr ? (fe_energy - sigma_c_energy) / 4 : 0.;
  }



  // K from the Gram matrices G_de(m, n) = int d_d phi_m d_e phi_n of the
  // scalar monomials: with sigma = lambda tr(eps) I + 2 mu eps,
  //   K_(c,m)(c',n) = lambda G_cc' + mu (delta_cc' (G_00 + G_11) + G_c'c).
  // The derivative of a monomial is a monomial, so each entry of G is one
  // of the cell's moments times the exponents: no quadrature loop over the
  // M^2 pairs.
  void
  LocalNeumannProblem::assemble_stiffness()
  {
    const unsigned int M      = exponents.size();
    const double       lambda = body.material().lambda();
    const double       mu     = body.material().mu();
    const double       scale  = 1. / (h * h);
    // G_de(m, n) = a_d(m) a_e(n) moment(alpha_m + alpha_n - e_d - e_e).
    const auto gram = [&](const unsigned int m,
                          const unsigned int n,
                          const unsigned int d,
                          const unsigned int e) {
      const auto &am = exponents[m];
      const auto &an = exponents[n];
      if (am[d] == 0 || an[e] == 0)
        return 0.;
      const unsigned int i = am[0] + an[0] - (d == 0) - (e == 0);
      const unsigned int j = am[1] + an[1] - (d == 1) - (e == 1);
      return scale * am[d] * an[e] * moment(i, j);
    };
    for (unsigned int m = 0; m < M; ++m)
      for (unsigned int n = 0; n <= m; ++n)
        {
          const double G[2][2] = {{gram(m, n, 0, 0), gram(m, n, 0, 1)},
                                  {gram(m, n, 1, 0), gram(m, n, 1, 1)}};
          for (unsigned int c = 0; c < 2; ++c)
            for (unsigned int d = 0; d < 2; ++d)
              {
                const double value =
                  lambda * G[c][d] +
                  mu * ((c == d ? G[0][0] + G[1][1] : 0.) + G[d][c]);
                stiffness(c * M + m, d * M + n) = value;
                // K is symmetric: K_(d,n)(c,m) = K_(c,m)(d,n).
                stiffness(d * M + n, c * M + m) = value;
              }
        }
  }



  const std::vector<double> &
  LocalNeumannProblem::monomial_values(const Point<2> &x) const
  {
    evaluate(x, false);
    return values;
  }



  void
  LocalNeumannProblem::add_traction(Vector<double>            &load,
                                    const Point<2>            &x,
                                    const Tensor<1, 2>        &t,
                                    const double               w,
                                    const std::array<bool, 2> &components) const
  {
    evaluate(x, false);
    const unsigned int M = exponents.size();
    for (unsigned int c = 0; c < 2; ++c)
      if (components[c])
        for (unsigned int m = 0; m < M; ++m)
          load(c * M + m) += t[c] * values[m] * w;
  }



  double
  LocalNeumannProblem::load_defect(const Vector<double> &load) const
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
    return size > 0 ? rigid_load / size : 0.;
  }



  void
  LocalNeumannProblem::remove_rigid_load(Vector<double> &load) const
  {
    // The three modes are mutually orthogonal (disjoint or complementary
    // supports), so each is removed on its own.
    for (const auto &mode : rigid)
      {
        double work = 0, length = 0;
        for (unsigned int a = 0; a < load.size(); ++a)
          {
            work += mode[a] * load(a);
            length += mode[a] * mode[a];
          }
        for (unsigned int a = 0; a < load.size(); ++a)
          load(a) -= work / length * mode[a];
      }
  }



  double
  LocalNeumannProblem::solve(const Vector<double> &load,
                             Vector<double>       &coefficients) const
  {
    factor.forward(forward_scratch, load);
    // L^T x = L^-1 load, by columns of L (no transposed copy of the
    // factor).
    const unsigned int n = load.size();
    coefficients.reinit(n, true);
    for (unsigned int i = n; i-- > 0;)
      {
        double x = forward_scratch(i);
        for (unsigned int j = i + 1; j < n; ++j)
          x -= factor(j, i) * coefficients(j);
        coefficients(i) = x / factor(i, i);
      }
    return load_defect(load);
  }



  void
  LocalNeumannProblem::whiten(const Vector<double> &load,
                              Vector<double>       &w) const
  {
    w.reinit(load.size(), true);
    factor.forward(w, load);
  }



  void
  LocalNeumannProblem::whiten_many(double            *loads,
                                   const unsigned int n_loads,
                                   const unsigned int stride) const
  {
    // Row by row of L: x_i = (r_i - sum_k<i L_ik x_k) / L_ii, each step
    // over all loads (L's rows are contiguous).
    const unsigned int N = n_coefficients();
    for (unsigned int i = 0; i < N; ++i)
      {
        const double *const row_i    = &factor(i, 0);
        double *const __restrict x_i = loads + i * stride;
        // Two columns of L at a time: one pass over x_i per two products.
        unsigned int k = 0;
        for (; k + 1 < i; k += 2)
          {
            const double        l = row_i[k], m = row_i[k + 1];
            const double *const x_k = loads + k * stride;
            const double *const y_k = x_k + stride;
            for (unsigned int r = 0; r < n_loads; ++r)
              x_i[r] -= l * x_k[r] + m * y_k[r];
          }
        for (; k < i; ++k)
          {
            const double        l   = row_i[k];
            const double *const x_k = loads + k * stride;
            for (unsigned int r = 0; r < n_loads; ++r)
              x_i[r] -= l * x_k[r];
          }
        for (unsigned int r = 0; r < n_loads; ++r)
          x_i[r] /= row_i[i];
      }
  }



  void
  LocalNeumannProblem::gram_lower(const double      *columns,
                                  const unsigned int n_columns,
                                  const unsigned int n_rows,
                                  double            *gram)
  {
    std::fill(gram, gram + n_columns * n_columns, 0.);
    // Two rows of @p columns at a time: one pass over the Gram matrix per
    // two products.
    unsigned int a = 0;
    for (; a + 1 < n_rows; a += 2)
      {
        const double *const x = columns + a * n_columns;
        const double *const y = x + n_columns;
        for (unsigned int i = 0; i < n_columns; ++i)
          {
            const double x_i = x[i], y_i = y[i];
            double *const __restrict row_i = gram + i * n_columns;
            for (unsigned int j = 0; j <= i; ++j)
              row_i[j] += x_i * x[j] + y_i * y[j];
          }
      }
    for (; a < n_rows; ++a)
      {
        const double *const x = columns + a * n_columns;
        for (unsigned int i = 0; i < n_columns; ++i)
          {
            const double x_i               = x[i];
            double *const __restrict row_i = gram + i * n_columns;
            for (unsigned int j = 0; j <= i; ++j)
              row_i[j] += x_i * x[j];
          }
      }
  }



  const Vector<double> &
  LocalNeumannProblem::whitened_kinematic_work() const
  {
    return whitened_sigma_c_work;
  }



  double
  LocalNeumannProblem::kinematic_energy() const
  {
    return sigma_c_energy;
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
        const SymmetricTensor<2, 2> plus  = sigma_hat + sigma_fe[q];
        result[0] += minus * material.strain(minus) * JxW[q];
        result[1] += plus * material.strain(plus) * JxW[q];
      }
    return result;
  }
} // namespace coulomb_adapt
