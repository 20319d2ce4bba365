#include <coulomb_adapt/core/elastic_material.h>
#include <coulomb_adapt/core/parameter_error.h>

#include <cmath>

namespace coulomb_adapt
{
  void
  MaterialConstants::declare_parameters(ParameterHandler &prm,
                                        const double default_youngs_modulus,
                                        const double default_poissons_ratio)
  {
    prm.declare_entry("Young's modulus",
                      Patterns::Tools::Convert<double>::to_string(
                        default_youngs_modulus),
                      Patterns::Double(),
                      "Young's modulus E of this body (MPa), E > 0.");
    prm.declare_entry("Poisson's ratio",
                      Patterns::Tools::Convert<double>::to_string(
                        default_poissons_ratio),
                      Patterns::Double(),
                      "Poisson's ratio nu of this body (dimensionless), "
                      "-1 < nu < 0.5.");
  }



  void
  MaterialConstants::parse_parameters(ParameterHandler  &prm,
                                      const std::string &path)
  {
    youngs_modulus = prm.get_double("Young's modulus");
    poissons_ratio = prm.get_double("Poisson's ratio");
    require_parameter(youngs_modulus > 0,
                      path + "/Young's modulus",
                      youngs_modulus,
                      "Young's modulus must be > 0 (MPa)");
    require_parameter(poissons_ratio > -1 && poissons_ratio < 0.5,
                      path + "/Poisson's ratio",
                      poissons_ratio,
                      "Poisson's ratio must lie in the open interval "
                      "(-1, 0.5)");
  }



  ElasticMaterial::ElasticMaterial(const MaterialConstants &constants,
                                   const PlaneModel         plane_model)
    : constants(constants)
    , plane_model(plane_model)
  {
    const double E         = constants.youngs_modulus;
    const double nu        = constants.poissons_ratio;
    mu_                    = E / (2. * (1. + nu));
    const double lambda_3d = E * nu / ((1. + nu) * (1. - 2. * nu));
    lambda_2d              = (plane_model == PlaneModel::plane_strain) ?
                               lambda_3d :
                               2. * mu_ * lambda_3d / (lambda_3d + 2. * mu_);
  }



  double
  ElasticMaterial::lambda() const
  {
    return lambda_2d;
  }



  double
  ElasticMaterial::mu() const
  {
    return mu_;
  }



  SymmetricTensor<2, 2>
  ElasticMaterial::stress(const SymmetricTensor<2, 2> &strain) const
  {
    return lambda_2d * trace(strain) * unit_symmetric_tensor<2>() +
           2. * mu_ * strain;
  }



  // Inverting sigma = lambda tr(eps) I + 2 mu eps: tr(sigma) = 2 (lambda +
  // mu) tr(eps), so eps = (sigma - lambda / (2 (lambda + mu)) tr(sigma) I)
  // / (2 mu), with the effective lambda of the 2D model.
  SymmetricTensor<2, 2>
  ElasticMaterial::strain(const SymmetricTensor<2, 2> &s) const
  {
    return (s - lambda_2d / (2. * (lambda_2d + mu_)) * trace(s) *
                  unit_symmetric_tensor<2>()) /
           (2. * mu_);
  }



  double
  ElasticMaterial::out_of_plane_stress(
    const SymmetricTensor<2, 2> &strain) const
  {
    if (plane_model == PlaneModel::plane_stress)
      return 0.;
    return constants.poissons_ratio * trace(stress(strain));
  }



  double
  ElasticMaterial::von_mises_stress(const SymmetricTensor<2, 2> &s,
                                    const double                 sigma_zz)
  {
    const double sxx = s[0][0], syy = s[1][1], sxy = s[0][1];
    return std::sqrt(0.5 * ((sxx - syy) * (sxx - syy) +
                            (syy - sigma_zz) * (syy - sigma_zz) +
                            (sigma_zz - sxx) * (sigma_zz - sxx)) +
                     3. * sxy * sxy);
  }
} // namespace coulomb_adapt
