#ifndef coulomb_adapt_scenes_scene_factory_h
#define coulomb_adapt_scenes_scene_factory_h

#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/scene.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * One scene of the registry: its name in `Scene/Name`, the declaration
     * of its subsection below `Scene` (empty for a variant that reads
     * another scene's subsection), and how it is made from the parameters
     * (with @p prm inside subsection `Scene`).
     */
    struct SceneEntry
    {
      std::string                             name;
      std::function<void(ParameterHandler &)> declare_parameters;
      std::function<std::unique_ptr<Scene>(ParameterHandler &,
                                           const Parameters &)>
        create;
    };

    /** Every scene of the program, in the order of `Scene/Name`'s
     * pattern. A new scene is a new file and one line in this list
     * (scene_factory.cc). */
    const std::vector<SceneEntry> &
    registered_scenes();

    /** The names of all scenes, '|'-separated (for Patterns::Selection). */
    std::string
    scene_names();

    /** Declare subsection `Scene`: the `Name` of the scene to solve, and
     * every scene's own subsection below it. */
    void
    declare_parameters(ParameterHandler &prm);

    /** Create the scene named in `Scene/Name` of @p prm, reading its
     * subsection (below `Scene`). */
    std::unique_ptr<Scene>
    create_scene(const Parameters &parameters, ParameterHandler &prm);
  } // namespace scenes
} // namespace coulomb_adapt

#endif
