#include <coulomb_adapt/output/stress_postprocessor.h>

namespace coulomb_adapt
{
  StressPostprocessor::StressPostprocessor(const ElasticMaterial &material)
    : material(material)
  {}



  void
  StressPostprocessor::evaluate_vector_field(
    const DataPostprocessorInputs::Vector<2> &inputs,
    std::vector<Vector<double>>              &computed_quantities) const
  {
    for (unsigned int p = 0; p < inputs.solution_gradients.size(); ++p)
      {
        Tensor<2, 2> grad;
        for (unsigned int c = 0; c < 2; ++c)
          grad[c] = inputs.solution_gradients[p][c];
        const SymmetricTensor<2, 2> strain = symmetrize(grad);
        const SymmetricTensor<2, 2> stress = material.stress(strain);
        const double                szz = material.out_of_plane_stress(strain);
        computed_quantities[p][0]       = stress[0][0];
        computed_quantities[p][1]       = stress[1][1];
        computed_quantities[p][2]       = stress[0][1];
        computed_quantities[p][3]       = szz;
        computed_quantities[p][4] =
          ElasticMaterial::von_mises_stress(stress, szz);
      }
  }



  std::vector<std::string>
  StressPostprocessor::get_names() const
  {
    return {"stress_xx", "stress_yy", "stress_xy", "stress_zz", "von_mises"};
  }



  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  StressPostprocessor::get_data_component_interpretation() const
  {
    return std::vector<
      DataComponentInterpretation::DataComponentInterpretation>(
      5, DataComponentInterpretation::component_is_scalar);
  }



  UpdateFlags
  StressPostprocessor::get_needed_update_flags() const
  {
    return update_gradients;
  }
} // namespace coulomb_adapt
