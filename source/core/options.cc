#include <coulomb_adapt/core/options.h>

namespace coulomb_adapt
{
  template <>
  const OptionNames<PlaneModel> &
  option_names<PlaneModel>()
  {
    static const OptionNames<PlaneModel> names = {
      {PlaneModel::plane_strain, "plane strain"},
      {PlaneModel::plane_stress, "plane stress"}};
    return names;
  }



  template <>
  const OptionNames<CellType> &
  option_names<CellType>()
  {
    static const OptionNames<CellType> names = {
      {CellType::quadrilateral, "quadrilateral"},
      {CellType::triangle, "triangle"}};
    return names;
  }



  template <>
  const OptionNames<OutputFormat> &
  option_names<OutputFormat>()
  {
    static const OptionNames<OutputFormat> names = {{OutputFormat::vtu, "vtu"},
                                                    {OutputFormat::hdf5,
                                                     "hdf5"}};
    return names;
  }



  template <>
  const OptionNames<WriteCycles> &
  option_names<WriteCycles>()
  {
    static const OptionNames<WriteCycles> names = {{WriteCycles::all, "all"},
                                                   {WriteCycles::last, "last"},
                                                   {WriteCycles::none, "none"}};
    return names;
  }



  template <>
  const OptionNames<LinearSolverType> &
  option_names<LinearSolverType>()
  {
    static const OptionNames<LinearSolverType> names = {
      {LinearSolverType::automatic, "auto"},
      {LinearSolverType::direct, "direct"},
      {LinearSolverType::amg, "amg"}};
    return names;
  }



  template <>
  const OptionNames<AdaptationStrategy> &
  option_names<AdaptationStrategy>()
  {
    static const OptionNames<AdaptationStrategy> names = {
      {AdaptationStrategy::uniform, "uniform"},
      {AdaptationStrategy::refine, "refine"},
      {AdaptationStrategy::remesh, "remesh"}};
    return names;
  }



  template <>
  const OptionNames<RefinementCriterion> &
  option_names<RefinementCriterion>()
  {
    static const OptionNames<RefinementCriterion> names = {
      {RefinementCriterion::size_ratio, "size ratio"},
      {RefinementCriterion::fixed_fraction, "fixed fraction"},
      {RefinementCriterion::fixed_number, "fixed number"},
      {RefinementCriterion::optimize, "optimize"}};
    return names;
  }



  template <>
  const OptionNames<RemeshingAlgorithm> &
  option_names<RemeshingAlgorithm>()
  {
    static const OptionNames<RemeshingAlgorithm> names = {
      {RemeshingAlgorithm::frontal_delaunay, "frontal-delaunay"},
      {RemeshingAlgorithm::delaunay, "delaunay"}};
    return names;
  }
} // namespace coulomb_adapt
