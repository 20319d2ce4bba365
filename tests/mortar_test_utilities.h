// A scene's two bodies and the mortar interface between them, for the
// tests of the interface's geometry.
#ifndef coulomb_adapt_tests_mortar_test_utilities_h
#define coulomb_adapt_tests_mortar_test_utilities_h

#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  namespace testing
  {
    /** The scene of @p settings, its bodies (slave = body 1, master =
     * body 2) on their initial meshes, set up, and the mortar between
     * them, not solved. */
    struct SceneInterface
    {
      explicit SceneInterface(
        const std::vector<std::pair<std::string, std::string>> &settings)
        : parameters(make_parameters(prm, settings))
        , scene(scenes::create_scene(parameters, prm))
        , slave(MPI_COMM_WORLD,
                *scene,
                0,
                parameters.mesh.cell_type,
                0,
                parameters.finite_elements)
        , master(MPI_COMM_WORLD,
                 *scene,
                 1,
                 parameters.mesh.cell_type,
                 0,
                 parameters.finite_elements)
      {
        slave.setup_system();
        master.setup_system();
        mortar.reinit(slave, master);
      }

      ParameterHandler       prm;
      Parameters             parameters;
      std::unique_ptr<Scene> scene;
      ElasticBody            slave, master;
      MortarInterface        mortar;
    };
  } // namespace testing
} // namespace coulomb_adapt

#endif
