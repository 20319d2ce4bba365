#include <coulomb_adapt/adaptation/adaptation_strategy.h>

#include <map>

namespace coulomb_adapt
{
  namespace
  {
    // Made on first use, so that it exists whatever the order in which the
    // strategies' files register themselves.
    std::map<AdaptationStrategy, std::unique_ptr<MeshAdaptationStrategy>> &
    registry()
    {
      static std::map<AdaptationStrategy,
                      std::unique_ptr<MeshAdaptationStrategy>>
        strategies;
      return strategies;
    }
  } // namespace



  bool
  register_mesh_adaptation_strategy(
    const AdaptationStrategy                strategy,
    std::unique_ptr<MeshAdaptationStrategy> implementation)
  {
    registry()[strategy] = std::move(implementation);
    return true;
  }



  const MeshAdaptationStrategy &
  mesh_adaptation_strategy(const AdaptationStrategy strategy)
  {
    const auto entry = registry().find(strategy);
    AssertThrow(entry != registry().end(),
                ExcMessage("no mesh adaptation strategy is registered for '" +
                           option_name(strategy) + "'"));
    return *entry->second;
  }
} // namespace coulomb_adapt
