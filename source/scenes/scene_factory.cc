#include <coulomb_adapt/scenes/blocks.h>
#include <coulomb_adapt/scenes/gmsh_file.h>
#include <coulomb_adapt/scenes/hertz.h>
#include <coulomb_adapt/scenes/manufactured.h>
#include <coulomb_adapt/scenes/patch.h>
#include <coulomb_adapt/scenes/punch.h>
#include <coulomb_adapt/scenes/scene_factory.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    namespace
    {
      // The scenes whose constructor needs only the plane model.
      template <typename SceneType>
      std::unique_ptr<Scene>
      with_plane_model(ParameterHandler &prm, const Parameters &parameters)
      {
        return std::make_unique<SceneType>(
          prm, parameters.finite_elements.plane_model);
      }
    } // namespace



    const std::vector<SceneEntry> &
    registered_scenes()
    {
      static const std::vector<SceneEntry> scenes = {
        {"blocks", Blocks::declare_parameters, with_plane_model<Blocks>},
        {"patch", Patch::declare_parameters, with_plane_model<Patch>},
        {"hertz",
         Hertz::declare_parameters,
         [](ParameterHandler &prm, const Parameters &parameters) {
           return std::make_unique<Hertz>(prm, parameters);
         }},
        // Hertz's geometry with a tangential load: Hertz declares both.
        {"cattaneo",
         nullptr,
         [](ParameterHandler &prm, const Parameters &parameters) {
           return std::make_unique<Hertz>(prm, parameters, true);
         }},
        {"punch", Punch::declare_parameters, with_plane_model<Punch>},
        {"gmsh",
         GmshFile::declare_parameters,
         [](ParameterHandler &prm, const Parameters &parameters) {
           return std::make_unique<GmshFile>(
             prm,
             parameters.finite_elements.plane_model,
             parameters.mesh.cell_type,
             parameters.adaptation.max_dofs,
             parameters.finite_elements.degree,
             parameters.mesh.global_refinements);
         }},
        {"manufactured",
         Manufactured::declare_parameters,
         with_plane_model<Manufactured>}};
      return scenes;
    }



    std::string
    scene_names()
    {
      std::string names;
      for (const SceneEntry &entry : registered_scenes())
        names += (names.empty() ? "" : "|") + entry.name;
      return names;
    }



    void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Scene");
      {
        prm.declare_entry("Name",
                          "blocks",
                          Patterns::Selection(scene_names()),
                          "The problem to solve: geometry, boundary "
                          "conditions, loads and materials of both bodies. "
                          "Each scene reads the subsection of the same name "
                          "below this one.");
        for (const SceneEntry &entry : registered_scenes())
          if (entry.declare_parameters)
            entry.declare_parameters(prm);
      }
      prm.leave_subsection();
    }



    std::unique_ptr<Scene>
    create_scene(const Parameters &parameters, ParameterHandler &prm)
    {
      std::unique_ptr<Scene> scene;
      prm.enter_subsection("Scene");
      try
        {
          const std::string name = prm.get("Name");
          for (const SceneEntry &entry : registered_scenes())
            if (entry.name == name)
              scene = entry.create(prm, parameters);
          // The Selection pattern has refused any other name.
          AssertThrow(scene != nullptr, ExcMessage("Unknown scene " + name));
        }
      catch (...)
        {
          prm.leave_subsection();
          throw;
        }
      prm.leave_subsection();
      return scene;
    }
  } // namespace scenes
} // namespace coulomb_adapt
