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
    stresses(const unsigned int b, const std::vector<Point<2>> &points) const = 0;

    /** Subdivisions per direction of the quadrature of a cell of body
     * @p b with diameter @p cell_diameter, so that a piecewise reference
     * field is integrated on its own pieces. */
    virtual unsigned int
    quadrature_subdivisions(const unsigned int b,
                            const double       cell_diameter) const = 0;

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
    stresses(const unsigned int b, const std::vector<Point<2>> &points) const override;
    unsigned int
    quadrature_subdivisions(const unsigned int b,
                            const double       cell_diameter) const override;
    std::string
    description() const override;

  private:
    std::array<const ElasticBody *, 2> bodies;
  };

  /**
   * A reference solution of the same scene on a finer mesh: both bodies
   * built with @p reference_refinements more uniform refinements and solved
   * with contact (quietly); its stress is evaluated at arbitrary points
   * across ranks (Utilities::MPI::RemotePointEvaluation). With
   * @p for_adapted_meshes, the meshes compared with it are not its
   * uniform ancestors: a cell gets as many quadrature subdivisions as
   * reference cells fit across it (diameter over the reference's largest
   * cell diameter, at most 2^reference_refinements), instead of
   * 2^reference_refinements everywhere (which on fine adapted meshes costs
   * cells x 4^R points for nothing).
   */
  class ReferenceSolutionStress : public ReferenceStress
  {
  public:
    ReferenceSolutionStress(const MPI_Comm                    mpi_communicator,
                            const Scene &                     scene,
                            const Parameters &                parameters,
                            const unsigned int                global_refinements,
                            const unsigned int                reference_refinements,
                            const bool for_adapted_meshes = false);
    ~ReferenceSolutionStress() override;
    std::vector<SymmetricTensor<2, 2>>
    stresses(const unsigned int b, const std::vector<Point<2>> &points) const override;
    unsigned int
    quadrature_subdivisions(const unsigned int b,
                            const double       cell_diameter) const override;
    std::string
    description() const override;
    /** Newton iterations of the reference contact solve. */
    unsigned int
    newton_iterations() const;

  private:
    ConditionalOStream                          quiet;
    unsigned int                                reference_refinements;
    bool                                        for_adapted_meshes;
    /** Largest cell diameter of each reference body. */
    std::array<double, 2>                       largest_cell_diameter;
    std::array<std::unique_ptr<ElasticBody>, 2> bodies;
    std::unique_ptr<ContactSolver>              contact_solver;
    unsigned int                                n_newton_iterations = 0;
  };

  /** The exact error of a solution and the effectivity of its estimate. */
  struct ExactErrorComparison
  {
    /** (3-8) normalised like (3-13), with sigma~ replaced by the reference:
     * sqrt((sum ||sigma - sigma_c||^2 + 2 int c) / sum ||sigma + sigma_c||^2). */
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
                           const ErrorEstimate &                     estimate,
                           const ReferenceStress &                   reference);
} // namespace coulomb_adapt

#endif
