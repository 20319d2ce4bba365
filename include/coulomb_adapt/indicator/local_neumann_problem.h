#ifndef coulomb_adapt_indicator_local_neumann_problem_h
#define coulomb_adapt_indicator_local_neumann_problem_h

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/dirichlet_data_lift.h>

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
   * reinit() assembles the cell's stiffness matrix K and factors it once,
   * K = L L^T, so that a cell can be solved for several loads (the
   * response to each free parameter of the edge tractions) at the cost of
   * two triangular solves each. Energy products of responses need only
   * one: with w = L^-1 l, the response u = K^-1 l has the energy
   * (u_i, u_j)_K = w_i . w_j (whiten()).
   */
  class LocalNeumannProblem
  {
  public:
    LocalNeumannProblem(const ElasticBody &body, const unsigned int degree);

    /** A problem of the same body and degree with its own scratch (for
     * one more thread): nothing of the current cell is copied. */
    LocalNeumannProblem(const LocalNeumannProblem &other);

    /** Assemble and factor the stiffness matrix of @p cell, the load of
     * the body force, and the stress of @p u_kinematic (ghosted) at the
     * quadrature points: the FE stress the errors are measured against. */
    void
    reinit(const DoFHandler<2>::active_cell_iterator &cell,
           const TrilinosWrappers::MPI::Vector       &u_kinematic);

    /** From the next reinit() on, the kinematic side is u_kinematic +
     * @p lift (dirichlet_data_lift.h): sigma_c below is then the stress of
     * that sum, except in the normalisation ||sigma^ + sigma_c|| (errors(),
     * whitened_normalisation_work()), which keeps the FE stress. Copies
     * share it; nullptr: none. */
    void
    set_kinematic_lift(const DirichletDataLiftField *lift);

    bool
    has_kinematic_lift() const
    {
      return kinematic_lift != nullptr;
    }

    /** For the normalisation with the FE stress sigma_fe (u_kinematic's,
     * without the lift): ||sigma^ + sigma_fe||^2 = ||sigma^ - sigma_c||^2 +
     * 4 (w . this + normalisation_offset()) for a response with whitened
     * load w. This is L^-1 of the work of (sigma_c + sigma_fe) / 2, the
     * offset (||sigma_fe||^2 - ||sigma_c||^2) / 4; without a lift,
     * whitened_kinematic_work() and 0. */
    const Vector<double> &
    whitened_normalisation_work() const;
    double
    normalisation_offset() const;

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

    /** The work of @p load on the rigid motions relative to its size (what
     * solve() returns, without solving). */
    double
    load_defect(const Vector<double> &load) const;

    /** Remove from @p load its (Euclidean) component on the rigid motions'
     * coefficients. That component moves the solution by a rigid motion
     * only, which carries no stress, but it would add to the whitened
     * load's length (the rigid motions are penalised, not removed). */
    void
    remove_rigid_load(Vector<double> &load) const;

    /** w = L^-1 @p load for a load orthogonal to the rigid motions: the
     * energy product of the responses to two loads is the dot product of
     * their w. */
    void
    whiten(const Vector<double> &load, Vector<double> &w) const;

    /** whiten() for @p n_loads loads at once, in place: @p loads is a
     * row-major matrix of n_coefficients() rows and @p stride >= n_loads
     * columns whose first n_loads columns are the loads (row a: entry a of
     * every load). Each step of the forward substitution is then one loop
     * over the loads: independent multiply-adds instead of the chain of
     * one dot product per entry of whiten() (the same to round-off). */
    void
    whiten_many(double            *loads,
                const unsigned int n_loads,
                const unsigned int stride) const;

    /** The lower triangle of the Gram matrix of the columns of the
     * row-major @p n_rows x @p n_columns matrix @p columns (whitened loads:
     * their energy products), into the row-major @p gram (n_columns^2;
     * entries above the diagonal are zero), summed row by row of
     * @p columns. */
    static void
    gram_lower(const double      *columns,
               const unsigned int n_columns,
               const unsigned int n_rows,
               double            *gram);

    /** L^-1 of the work of the FE stress on each basis function: for a
     * response u with whitened load w, int sigma_c : eps(u) = w . this. */
    const Vector<double> &
    whitened_kinematic_work() const;

    /** ||sigma_c||^2 on the cell (energy norm). With the whitened load w of
     * a response sigma^, ||sigma^ - sigma_c||^2 = |w - w_c|^2 + this -
     * |w_c|^2 for w_c = whitened_kinematic_work(): the last two terms are
     * the part of sigma_c outside the local problem's stress space. */
    double
    kinematic_energy() const;

    /** ||sigma^ - sigma_c||^2 and ||sigma^ + sigma_c||^2 on the cell
     * (energy norm, N per unit thickness), sigma^ = K eps(u^), from the
     * quadrature points (no cancellation when sigma^ is close to
     * sigma_c). */
    std::array<double, 2>
    errors(const Vector<double> &coefficients) const;

  private:
    // Values (and with @p with_gradients their gradients) of the scalar
    // monomials at x. The loads need the values only.
    void
    evaluate(const Point<2> &x, const bool with_gradients = true) const;

    // K from the cell's monomial moments (see reinit()).
    void
    assemble_stiffness();

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
    // Per quadrature point: the monomials' gradients, JxW, sigma_c, and
    // (scratch) the FE strain.
    std::vector<std::vector<Tensor<1, 2>>> gradients_at;
    std::vector<double>                    JxW;
    std::vector<SymmetricTensor<2, 2>>     sigma_c, strains;
    // The FE stress, for the normalisation (sigma_c without the lift).
    std::vector<SymmetricTensor<2, 2>> sigma_fe;
    const DirichletDataLiftField      *kinematic_lift = nullptr;
    Vector<double>                     sigma_fe_work, whitened_sigma_fe_work;
    double                             fe_energy = 0;
    // moment(i, j) = int_cell xi^i eta^j dx in the scaled coordinates, up
    // to the total degree 2 (degree - 1) of the stiffness integrand.
    Table<2, double> moment;
    // The stiffness matrix with the rigid motions penalised (scratch of
    // reinit()), its Cholesky factor L, the body force load, the work of
    // sigma_c on each basis function, L^-1 of that work, and ||sigma_c||^2.
    FullMatrix<double>                 stiffness, factor;
    Vector<double>                     body_force, sigma_c_work;
    Vector<double>                     whitened_sigma_c_work;
    double                             sigma_c_energy = 0;
    mutable Vector<double>             forward_scratch;
    std::array<std::vector<double>, 3> rigid;
  };
} // namespace coulomb_adapt

#endif
