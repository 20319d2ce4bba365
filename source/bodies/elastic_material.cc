#include <coulomb_adapt/bodies/elastic_material.h>

#include <cmath>

namespace coulomb_adapt
{
  ElasticMaterial::ElasticMaterial(const MaterialConstants &constants,
                                   const PlaneModel         plane_model)
    : constants(constants)
    , plane_model(plane_model)
  {
    const double E  = constants.youngs_modulus;
    const double nu = constants.poissons_ratio;
    mu_             = E / (2. * (1. + nu));
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
