#ifndef coulomb_adapt_core_options_h
#define coulomb_adapt_core_options_h

#include <deal.II/base/exceptions.h>

#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /** The 2D reduction of the elastic bodies (`Finite elements/Plane
   * model`). */
  enum class PlaneModel
  {
    plane_strain,
    plane_stress
  };

  /** The reference cell of the meshes of the built-in scenes (`Mesh/Cell
   * type`). */
  enum class CellType
  {
    quadrilateral,
    triangle
  };

  /** `Output/Format`: the file format of the per-cycle fields. */
  enum class OutputFormat
  {
    vtu,
    hdf5
  };

  /** `Output/Write cycles`: which cycles' fields are written. */
  enum class WriteCycles
  {
    all,
    last,
    none
  };

  /** `Linear solver/Type`. */
  enum class LinearSolverType
  {
    /** Direct up to a number of DoFs, Krylov + AMG above ("auto"). */
    automatic,
    direct,
    amg
  };

  /** `Adaptation/Strategy`: how the mesh changes between two cycles. */
  enum class AdaptationStrategy
  {
    uniform,
    refine,
    remesh
  };

  /** `Adaptation/Refinement criterion`: which cells 'refine' flags. */
  enum class RefinementCriterion
  {
    size_ratio,
    fixed_fraction,
    fixed_number,
    optimize
  };

  /** `Adaptation/Remeshing algorithm`: gmsh's 2D meshing algorithm for
   * `Strategy = remesh`. */
  enum class RemeshingAlgorithm
  {
    frontal_delaunay,
    delaunay
  };

  /**
   * The names an option's values have in the parameter file, in the order
   * of its Selection pattern. An option is parsed once into its enum; the
   * pattern, the parsing and the messages that print the value all read
   * this one table, so that they cannot drift apart.
   */
  template <typename Option>
  using OptionNames = std::vector<std::pair<Option, std::string>>;

  /** The table of @p Option (one specialisation per enum above, in
   * options.cc). */
  template <typename Option>
  const OptionNames<Option> &
  option_names();

  /** "a|b|c": the Patterns::Selection of @p Option. */
  template <typename Option>
  std::string
  option_pattern()
  {
    std::string pattern;
    for (const auto &[value, name] : option_names<Option>())
      pattern += (pattern.empty() ? "" : "|") + name;
    return pattern;
  }

  /** The name of @p value in the parameter file. */
  template <typename Option>
  const std::string &
  option_name(const Option value)
  {
    for (const auto &[v, name] : option_names<Option>())
      if (v == value)
        return name;
    Assert(false, dealii::ExcInternalError());
    return option_names<Option>().front().second;
  }

  /** The value named @p name; the Selection pattern has already refused
   * every other name, so one here is an internal error. */
  template <typename Option>
  Option
  parse_option(const std::string &name)
  {
    for (const auto &[value, n] : option_names<Option>())
      if (n == name)
        return value;
    AssertThrow(false,
                dealii::ExcMessage("'" + name + "' is none of " +
                                   option_pattern<Option>()));
    return option_names<Option>().front().first;
  }

  template <>
  const OptionNames<PlaneModel> &
  option_names<PlaneModel>();
  template <>
  const OptionNames<CellType> &
  option_names<CellType>();
  template <>
  const OptionNames<OutputFormat> &
  option_names<OutputFormat>();
  template <>
  const OptionNames<WriteCycles> &
  option_names<WriteCycles>();
  template <>
  const OptionNames<LinearSolverType> &
  option_names<LinearSolverType>();
  template <>
  const OptionNames<AdaptationStrategy> &
  option_names<AdaptationStrategy>();
  template <>
  const OptionNames<RefinementCriterion> &
  option_names<RefinementCriterion>();
  template <>
  const OptionNames<RemeshingAlgorithm> &
  option_names<RemeshingAlgorithm>();
} // namespace coulomb_adapt

#endif
