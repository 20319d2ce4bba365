#ifndef coulomb_adapt_indicator_exact_error_h
#define coulomb_adapt_indicator_exact_error_h

#include <deal.II/base/conditional_ostream.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <array>
#include <memory>
#include <vector>

namespace coulomb_adapt
{
  class ContactSolver;

  /** The stress the exact error (3-8) compares sigma_c with. */
  class ReferenceStress
  {
  public:
    virtual ~ReferenceStress() = default;

    /** sigma at @p points of body @p b (collective: every rank calls it,
     * with its own points). */
    virtual std::vector<SymmetricTensor<2, 2>>
    stresses(const unsigned int           b,
             const std::vector<Point<2>> &points) const = 0;

    /** Subdivisions per direction of the quadrature of a cell of the
     * judged meshes, so that a piecewise reference field is integrated on
     * its own pieces. */
    virtual unsigned int
    quadrature_subdivisions() const = 0;

    /** "exact solution" or "reference solution (N DoFs)". */
    virtual std::string
    description() const = 0;
  };

  /** The scenes' exact solution (manufactured problems). */
  class ExactSolutionStress : public ReferenceStress
  {
  public:
    ExactSolutionStress(const std::array<const ElasticBody *, 2> &bodies);
    std::vector<SymmetricTensor<2, 2>>
    stresses(const unsigned int           b,
             const std::vector<Point<2>> &points) const override;
    unsigned int
    quadrature_subdivisions() const override;
    std::string
    description() const override;

  private:
    std::array<const ElasticBody *, 2> bodies;
  };

  /**
   * A body on the current mesh of @p judged (body @p body_index of
   * @p scene) refined @p refinements times uniformly, set up and
   * assembled: every cell of the judged mesh is split into 4^refinements
   * cells of the new one. Triangles: the judged mesh, gathered from all
   * ranks, becomes the coarse mesh (ElasticBody::replace_mesh, the
   * remesher's path). Quadrilaterals: the judged mesh's refinement history
   * (hanging nodes included) is replayed on the scene's coarse mesh, cell
   * by CellId.
   */
  std::unique_ptr<ElasticBody>
  make_refined_body(const ElasticBody &judged,
                    const Scene       &scene,
                    const unsigned int body_index,
                    const Parameters  &parameters,
                    const unsigned int refinements);

  /** The strain energy U = 1/2 int sigma : epsilon of the displacement
   * @p displacement (with ghost entries) of @p body. */
  double
  strain_energy(const ElasticBody                   &body,
                const TrilinosWrappers::MPI::Vector &displacement);

  /**
   * The exact error extrapolated from a reference on the judged meshes
   * refined R times (theory.md section 8). With nested spaces, the error
   * of the judged solution is e_h^2 = a^2 + e_R^2 (a = @p against_reference,
   * the computed exact error) and the one of level R - 1 is
   * e_{R-1}^2 = d^2 + e_R^2 (d = @p own_error, the change from R - 1 to R).
   * If the error falls by the same factor from level to level,
   * e_h^2 / e_R^2 = (e_{R-1}^2 / e_R^2)^R, which fixes e_R: the root
   * t = d^2 / e_R^2 > 0 of (1 + t)^R = 1 + (a^2 / d^2) t. Returns
   * sqrt(a^2 + e_R^2), or 0 when there is no such root (R < 2, or
   * R d^2 >= a^2: the levels are not in the asymptotic range).
   */
  double
  extrapolated_exact_error(const double       against_reference,
                           const double       own_error,
                           const unsigned int refinements);



  /**
   * A reference solution of the same scene: the judged meshes themselves
   * (both bodies, as they are in this cycle) refined @p refinements times
   * uniformly and solved with contact (quietly), so that the reference is
   * finer than the judged meshes everywhere (theory.md section 8). Its
   * stress is evaluated at arbitrary points across ranks, each in the
   * owned cell that holds it (a bounding-box tree and the reference
   * cell's own test; deal.II 9.4's RemotePointEvaluation took neighbours
   * on triangles).
   *
   * Its own error is estimated from the solution one refinement coarser
   * (refinements - 1; the judged FE solution itself when refinements = 1):
   * the change from that level to this one. Since the spaces are nested,
   * the change from level R - 1 to R bounds the error of level R from
   * above when the error falls by at least sqrt(2) per refinement (and
   * from below it bounds the error of level R - 1).
   */
  class ReferenceSolutionStress : public ReferenceStress
  {
  public:
    ReferenceSolutionStress(const Scene      &scene,
                            const Parameters &parameters,
                            const std::array<const ElasticBody *, 2> &judged,
                            const unsigned int refinements,
                            const bool         estimate_own_error = true);
    ~ReferenceSolutionStress() override;
    std::vector<SymmetricTensor<2, 2>>
    stresses(const unsigned int           b,
             const std::vector<Point<2>> &points) const override;
    /** 2^refinements: the judged cells' pieces. */
    unsigned int
    quadrature_subdivisions() const override;
    std::string
    description() const override;
    /** R, the refinements of the judged meshes. */
    unsigned int
    n_refinements() const;
    /** Newton iterations of the reference contact solve. */
    unsigned int
    newton_iterations() const;
    types::global_dof_index
    n_dofs() const;
    /** Reference body @p b, solved. */
    const ElasticBody &
    body(const unsigned int b) const;
    /** The reference's strain energy of body @p b. */
    double
    strain_energy(const unsigned int b) const;
    /** The reference's own error, normalised like epsilon:
     * ||sigma_R - sigma_{R-1}|| / ||sigma_R + sigma_{R-1}|| over both
     * bodies (0 unless estimated). */
    double
    own_error() const;
    /** The same from the strain energies:
     * sqrt(|U_R - U_{R-1}| / (4 U_R)). */
    double
    own_error_from_energy() const;

  private:
    ConditionalOStream                          quiet;
    unsigned int                                refinements;
    std::array<std::unique_ptr<ElasticBody>, 2> bodies;
    unsigned int                                n_newton_iterations = 0;
    std::array<double, 2>                       energies            = {{0, 0}};
    double                                      epsilon_own         = 0;
    double                                      epsilon_own_energy  = 0;
  };

  /** The stress difference of displacement fields on the judged meshes and
   * a reference, integrated with the quadrature of the pieces. */
  struct StressDifference
  {
    /** ||sigma_ref - sigma_h||^2_{sigma,E} per active cell of each body
     * (entries of locally owned cells). */
    std::array<Vector<double>, 2> cell_squared;
    /** sum of ||sigma_ref - sigma_h||^2 over both bodies. */
    double difference_squared = 0;
    /** sum of ||sigma_ref + sigma_h||^2 over both bodies. */
    double sum_squared = 0;
  };

  /** Compare the stresses of @p displacements (with ghost entries) on
   * @p bodies with @p reference, each cell integrated on @p subdivisions x
   * @p subdivisions pieces. Collective. */
  StressDifference
  compare_stresses(
    const std::array<const ElasticBody *, 2>                   &bodies,
    const std::array<const TrilinosWrappers::MPI::Vector *, 2> &displacements,
    const ReferenceStress                                      &reference,
    const unsigned int                                          subdivisions);

  /** The exact error of a solution and the effectivity of its estimate. */
  struct ExactErrorComparison
  {
    /** (3-8) normalised like (3-13), with sigma~ replaced by the reference:
     * sqrt((sum ||sigma - sigma_c||^2 + 2 int c) / sum ||sigma + sigma_c||^2).
     */
    double epsilon_exact = 0;
    /** epsilon / epsilon_exact. */
    double effectivity = 0;
    /** Statistics of the element effectivities e_E / e_E,exact over the
     * cells of both bodies whose exact contribution is not negligible
     * (above 1e-12 of the largest). */
    double       element_effectivity_mean = 0;
    double       element_effectivity_std  = 0;
    double       element_effectivity_min  = 0;
    double       element_effectivity_max  = 0;
    unsigned int n_elements               = 0;
  };

  ExactErrorComparison
  compare_with_exact_error(const std::array<const ElasticBody *, 2> &bodies,
                           const ErrorEstimate                      &estimate,
                           const ReferenceStress                    &reference);
} // namespace coulomb_adapt

#endif
