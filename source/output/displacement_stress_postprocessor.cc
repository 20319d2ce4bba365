#include <coulomb_adapt/output/displacement_stress_postprocessor.h>

namespace coulomb_adapt
{
  DisplacementStressPostprocessor::DisplacementStressPostprocessor(
    const ElasticMaterial &material)
    : material(material)
  {}



  void
  DisplacementStressPostprocessor::evaluate_vector_field(
    const DataPostprocessorInputs::Vector<2> &inputs,
    std::vector<Vector<double>>              &computed_quantities) const
  {
    for (unsigned int p = 0; p < inputs.solution_gradients.size(); ++p)
      {
        Tensor<2, 2> grad;
        for (unsigned int c = 0; c < 2; ++c)
          {
            computed_quantities[p][c] = inputs.solution_values[p][c];
            grad[c]                   = inputs.solution_gradients[p][c];
          }
        const SymmetricTensor<2, 2> strain = symmetrize(grad);
        const SymmetricTensor<2, 2> stress = material.stress(strain);
        const double                szz = material.out_of_plane_stress(strain);
        computed_quantities[p][2]       = stress[0][0];
        computed_quantities[p][3]       = stress[1][1];
        computed_quantities[p][4]       = stress[0][1];
        computed_quantities[p][5]       = szz;
        computed_quantities[p][6] =
          ElasticMaterial::von_mises_stress(stress, szz);
      }
  }



  std::vector<std::string>
  DisplacementStressPostprocessor::get_names() const
  {
    return {"displacement",
            "displacement",
            "stress_xx",
            "stress_yy",
            "stress_xy",
            "stress_zz",
            "von_mises"};
  }



  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  DisplacementStressPostprocessor::get_data_component_interpretation() const
  {
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(7, DataComponentInterpretation::component_is_scalar);
    interpretation[0] = interpretation[1] =
      DataComponentInterpretation::component_is_part_of_vector;
    return interpretation;
  }



  UpdateFlags
  DisplacementStressPostprocessor::get_needed_update_flags() const
  {
    return update_values | update_gradients;
  }
} // namespace coulomb_adapt
