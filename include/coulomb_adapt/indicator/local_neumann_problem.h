#ifndef coulomb_adapt_indicator_local_neumann_problem_h
#define coulomb_adapt_indicator_local_neumann_problem_h

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>

#include <array>
#include <memory>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The Neumann problem of linear elasticity on one cell, in the complete
   * polynomials of degree P in the cell's scaled coordinates
   * (x - centre) / diameter: the local problems of the element
   * equilibration technique (theory.md section 7.3). The same basis serves
   * triangles and quadrilaterals; it contains the rigid motions, which are
   * removed from the solution (the data must be self-equilibrated).
   *
   * reinit() assembles the cell's stiffness matrix and factors it once, so
   * that a cell can be solved for several loads (the response to each free
   * parameter of the edge tractions) at the cost of a matrix-vector
   * product each.
   */
  class LocalNeumannProblem
  {
  public:
    LocalNeumannProblem(const ElasticBody &body, const unsigned int degree);

    /** Assemble and factor the stiffness matrix of @p cell, the load of
     * the body force, and the stress of @p u_kinematic (ghosted) at the
     * quadrature points: the FE stress the errors are measured against. */
    void
    reinit(const DoFHandler<2>::active_cell_iterator &cell,
           const TrilinosWrappers::MPI::Vector       &u_kinematic);

    /** Number of coefficients of a solution (x block, then y block). */
    unsigned int
    n_coefficients() const;

    /** The load of the body force on the current cell. */
    const Vector<double> &
    body_force_load() const;

    /** The values of the scalar basis functions (monomials) at @p x: the
     * work of a traction t at x is t_c times these in block c. Valid until
     * the next call of a member function. */
    const std::vector<double> &
    monomial_values(const Point<2> &x) const;

    /** Add the work of the traction @p t at @p x with weight @p w to
     * @p load, on the components marked in @p components. */
    void
    add_traction(Vector<double>            &load,
                 const Point<2>            &x,
                 const Tensor<1, 2>        &t,
                 const double               w,
                 const std::array<bool, 2> &components) const;

    /** The solution orthogonal to the rigid motions for a load orthogonal
     * to them. Returns the load's work on the rigid motions relative to
     * its size: the load is self-equilibrated to this accuracy. */
    double
    solve(const Vector<double> &load, Vector<double> &coefficients) const;

    /** int sigma_c : eps(v): the work of the FE stress on v. */
    double
    kinematic_work(const Vector<double> &v) const;

    /** ||sigma^ - sigma_c||^2 and ||sigma^ + sigma_c||^2 on the cell
     * (energy norm, N per unit thickness), sigma^ = K eps(u^), from the
     * quadrature points (no cancellation when sigma^ is close to
     * sigma_c). */
    std::array<double, 2>
    errors(const Vector<double> &coefficients) const;

  private:
    // Values and gradients of the scalar monomials at x.
    void
    evaluate(const Point<2> &x) const;

    const ElasticBody                       &body;
    const unsigned int                       degree;
    std::vector<std::array<unsigned int, 2>> exponents;
    std::unique_ptr<Quadrature<2>>           cell_rule;
    std::unique_ptr<FEValues<2>>             fe_values;
    Point<2>                                 centre;
    double                                   h = 1;
    // Scratch of evaluate().
    mutable std::vector<double>       values;
    mutable std::vector<Tensor<1, 2>> gradients;
    // Per quadrature point: the monomials' gradients, JxW, sigma_c.
    std::vector<std::vector<Tensor<1, 2>>> gradients_at;
    std::vector<double>                    JxW;
    std::vector<SymmetricTensor<2, 2>>     sigma_c;
    // The stiffness matrix with the rigid motions penalised (scratch of
    // reinit()), its Cholesky factor, the body force load and the work of
    // sigma_c on each basis function.
    FullMatrix<double>                 stiffness;
    LAPACKFullMatrix<double>           factor;
    Vector<double>                     body_force, sigma_c_work;
    std::array<std::vector<double>, 3> rigid;
  };
} // namespace coulomb_adapt

#endif
