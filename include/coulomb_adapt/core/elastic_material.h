#ifndef coulomb_adapt_core_elastic_material_h
#define coulomb_adapt_core_elastic_material_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <coulomb_adapt/core/parameters.h>

#include <string>

namespace coulomb_adapt
{
  /**
   * Isotropic linear elastic material constants of one body.
   */
  struct MaterialConstants
  {
    /** Young's modulus E (MPa). */
    double youngs_modulus;
    /** Poisson's ratio nu (dimensionless). */
    double poissons_ratio;

    /** Declare `Young's modulus` and `Poisson's ratio` in the current
     * subsection, with the scene's defaults. */
    static void
    declare_parameters(ParameterHandler &prm,
                       const double      default_youngs_modulus,
                       const double      default_poissons_ratio);

    /** Read and check them; @p path names the subsection for messages. */
    void
    parse_parameters(ParameterHandler &prm, const std::string &path);
  };

  /**
   * Hooke's law of an isotropic body reduced to 2D. Both reductions have
   * the form sigma = lambda tr(eps) I + 2 mu eps with an effective lambda:
   * plane strain keeps the 3D value, plane stress uses
   * 2 mu lambda / (lambda + 2 mu).
   */
  class ElasticMaterial
  {
  public:
    ElasticMaterial(const MaterialConstants &constants,
                    const PlaneModel         plane_model);

    /** Effective first Lamé parameter of the 2D model (MPa). */
    double
    lambda() const;

    /** Shear modulus (MPa). */
    double
    mu() const;

    SymmetricTensor<2, 2>
    stress(const SymmetricTensor<2, 2> &strain) const;

    /** The compliance K^-1 of the 2D model: the strain with this stress.
     * sigma : strain(sigma) is the energy density of the 2D model (in
     * plane strain it includes the work of sigma_zz, which is 0). */
    SymmetricTensor<2, 2>
    strain(const SymmetricTensor<2, 2> &stress) const;

    /** sigma_zz: nu (sigma_xx + sigma_yy) in plane strain, 0 in plane
     * stress. */
    double
    out_of_plane_stress(const SymmetricTensor<2, 2> &strain) const;

    /** Von Mises stress of the 3D state (in-plane stress plus sigma_zz). */
    static double
    von_mises_stress(const SymmetricTensor<2, 2> &stress,
                     const double                 sigma_zz);

  private:
    MaterialConstants constants;
    PlaneModel        plane_model;
    double            lambda_2d;
    double            mu_;
  };
} // namespace coulomb_adapt

#endif
