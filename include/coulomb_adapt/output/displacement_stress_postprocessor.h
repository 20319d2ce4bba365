#ifndef coulomb_adapt_output_displacement_stress_postprocessor_h
#define coulomb_adapt_output_displacement_stress_postprocessor_h

#include <deal.II/numerics/data_postprocessor.h>

#include <coulomb_adapt/core/elastic_material.h>

namespace coulomb_adapt
{
  /**
   * The fields ParaView shows from a body's solution, computed at the
   * output points from one evaluation of it: the displacement (a vector)
   * and, from its gradient, sigma_xx, sigma_yy, sigma_xy, sigma_zz and the
   * von Mises stress (MPa), one data set for both.
   */
  class DisplacementStressPostprocessor : public DataPostprocessor<2>
  {
  public:
    explicit DisplacementStressPostprocessor(const ElasticMaterial &material);

    void
    evaluate_vector_field(
      const DataPostprocessorInputs::Vector<2> &inputs,
      std::vector<Vector<double>> &computed_quantities) const override;

    std::vector<std::string>
    get_names() const override;

    std::vector<DataComponentInterpretation::DataComponentInterpretation>
    get_data_component_interpretation() const override;

    UpdateFlags
    get_needed_update_flags() const override;

  private:
    const ElasticMaterial material;
  };
} // namespace coulomb_adapt

#endif
