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
    std::string
    scene_names()
    {
      return "blocks|patch|hertz|cattaneo|punch|gmsh|manufactured";
    }



    void
    declare_parameters(ParameterHandler &prm)
    {
      Blocks::declare_parameters(prm);
      Patch::declare_parameters(prm);
      Hertz::declare_parameters(prm);
      Punch::declare_parameters(prm);
      GmshFile::declare_parameters(prm);
      Manufactured::declare_parameters(prm);
    }



    std::unique_ptr<Scene>
    create_scene(const Parameters &parameters, ParameterHandler &prm)
    {
      const std::string     &name  = parameters.scene.name;
      const PlaneModel       model = parameters.finite_elements.plane_model;
      std::unique_ptr<Scene> scene;
      prm.enter_subsection("Scene");
      try
        {
          if (name == "blocks")
            scene = std::make_unique<Blocks>(prm, model);
          else if (name == "patch")
            scene = std::make_unique<Patch>(prm, model);
          else if (name == "hertz")
            scene = std::make_unique<Hertz>(prm, parameters);
          else if (name == "cattaneo")
            scene = std::make_unique<Hertz>(prm, parameters, true);
          else if (name == "punch")
            scene = std::make_unique<Punch>(prm, model);
          else if (name == "gmsh")
            scene =
              std::make_unique<GmshFile>(prm, model, parameters.mesh.cell_type);
          else if (name == "manufactured")
            scene = std::make_unique<Manufactured>(prm, model);
        }
      catch (...)
        {
          prm.leave_subsection();
          throw;
        }
      prm.leave_subsection();
      AssertThrow(scene != nullptr, ExcMessage("Unknown scene " + name));
      return scene;
    }
  } // namespace scenes
} // namespace coulomb_adapt
