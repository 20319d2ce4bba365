#ifndef coulomb_adapt_adaptation_adaptation_strategy_h
#define coulomb_adapt_adaptation_adaptation_strategy_h

#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/adaptation/optimal_size.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <array>
#include <memory>

namespace coulomb_adapt
{
  /**
   * One way of changing both bodies' meshes from one cycle to the next
   * (`Adaptation/Strategy`): ASPECT's interface and plugins at the scale
   * of this program. adapt_meshes() plans the optimal mesh of theory.md
   * section 4 for the strategies that want it and hands them the plan; a
   * strategy only changes the meshes. A new strategy is a class in its own
   * file that registers itself there in one line, and its name in the
   * option table (core/options.cc).
   */
  class MeshAdaptationStrategy
  {
  public:
    virtual ~MeshAdaptationStrategy() = default;

    /** Whether the strategy builds the optimal mesh from the size ratios
     * r_E (then computed before change_meshes()). */
    virtual bool
    plans_optimal_mesh(const parameters::Adaptation &parameters) const = 0;

    /** Change the meshes of @p bodies; @p ratios is the plan if
     * plans_optimal_mesh(), else empty. Adds what it did to @p report. */
    virtual void
    change_meshes(const std::array<ElasticBody *, 2> &bodies,
                  const ErrorEstimate                &estimate,
                  const OptimalSizeRatios            &ratios,
                  const parameters::Adaptation       &parameters,
                  const unsigned int                  degree,
                  const double                        aimed_error,
                  MeshAdaptationReport               &report) const = 0;
  };

  /** Put @p implementation in the registry under @p strategy: one line
   * at the end of the strategy's file,
   *   const bool registered = register_mesh_adaptation_strategy(...);
   * run when the library is loaded. Returns true. */
  bool
  register_mesh_adaptation_strategy(
    const AdaptationStrategy                strategy,
    std::unique_ptr<MeshAdaptationStrategy> implementation);

  /** The strategy registered under @p strategy. */
  const MeshAdaptationStrategy &
  mesh_adaptation_strategy(const AdaptationStrategy strategy);
} // namespace coulomb_adapt

#endif
