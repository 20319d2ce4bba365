#ifndef coulomb_adapt_indicator_recovered_stress_h
#define coulomb_adapt_indicator_recovered_stress_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/quadrature_stress.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** How the smoothed stress of the indicator is obtained (theory.md §3.3). */
  enum class StressRecoveryMethod
  {
    /** ZZ1: global L2 projection onto the continuous FE space (a mass
     * system with one right-hand side per stress component). */
    l2_projection,
    /** Superconvergent patch recovery (Zienkiewicz and Zhu 1992): around
     * each vertex, a polynomial of degree p fitted by least squares to the
     * stress at the Gauss points of order p of the cells sharing the
     * vertex; nodal values from these polynomials (spr_recovery.cc).
     * Degrees 1 and 2. */
    spr
  };

  /** "zz" or "spr", as in the parameter file and summary.json. */
  std::string
  to_string(const StressRecoveryMethod method);

  /**
   * The smoothed stress sigma~ of one body: a continuous field in the
   * body's own scalar finite element space (FE_Q(p) or FE_SimplexP(p), the
   * degree of the displacement), one vector per component (sigma_xx,
   * sigma_yy, sigma_xy) of the 2D model, with the body's hanging-node
   * constraints so that it is continuous on adapted quadrilateral meshes
   * too.
   *
   * Only the in-plane components are recovered: in plane strain sigma_zz
   * is not an independent field but nu (sigma_xx + sigma_yy), and the
   * energy norm of the 2D model (K^-1 of ElasticMaterial::strain) already
   * accounts for it.
   */
  class RecoveredStress
  {
  public:
    /** deal.II's distributed vector: the ZZ solve's own type, so the
     * solution is kept without a copy into another library's layout. */
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /** Set up the stress space on @p body's current mesh. */
    explicit RecoveredStress(const ElasticBody &body);

    /** Recover sigma~ from the raw stress K eps(u) of @p raw_stress (same
     * body and mesh). ZZ integrates the stress and weights @p raw_stress
     * holds; SPR samples K eps(u) of its displacement at its own points
     * (the Gauss points of order p). */
    void
    recover(const QuadratureStress    &raw_stress,
            const StressRecoveryMethod method);

    /** The scalar space that each component lives in. */
    const DoFHandler<2> &
    dof_handler() const;

    /** The nodal values of component @p c (0, 1, 2 = xx, yy, xy), with
     * ghost entries. */
    const VectorType &
    component(const unsigned int c) const;

    /** sigma~ (xx, yy, xy) at the points of the body's cell quadrature on
     * the locally owned or ghost @p cell of dof_handler(). */
    void
    get_quadrature_values(const DoFHandler<2>::active_cell_iterator &cell,
                          std::vector<Tensor<1, 3>> &values) const;

  private:
    void
    project_l2(const QuadratureStress &raw_stress);
    /** Implemented in spr_recovery.cc. */
    void
    recover_spr(const TrilinosWrappers::MPI::Vector &displacement);

    const ElasticBody &body;
    /** The scalar base element of the body's displacement space. */
    const FiniteElement<2>   &fe;
    DoFHandler<2>             dofs;
    IndexSet                  owned_dofs;
    IndexSet                  relevant_dofs;
    AffineConstraints<double> constraints;
    /** Owned and ghost (locally relevant) entries of the components. */
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    std::array<VectorType, 3>                          components;
    /** phi_k at the points of the body's cell quadrature (k, q): the
     * values of Lagrange shape functions do not depend on the mapping. */
    FullMatrix<double> shape_values;
  };

} // namespace coulomb_adapt

#endif
