#ifndef coulomb_adapt_scenes_scene_factory_h
#define coulomb_adapt_scenes_scene_factory_h

#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/scene.h>

#include <memory>
#include <string>

namespace coulomb_adapt
{
  namespace scenes
  {
    /** The names of all scenes, '|'-separated (for Patterns::Selection). */
    std::string
    scene_names();

    /** Declare every scene's subsection; call inside subsection `Scene`. */
    void
    declare_parameters(ParameterHandler &prm);

    /** Create the scene chosen in @p parameters, reading its subsection
     * (below `Scene`) of @p prm. */
    std::unique_ptr<Scene>
    create_scene(const Parameters &parameters, ParameterHandler &prm);
  } // namespace scenes
} // namespace coulomb_adapt

#endif
