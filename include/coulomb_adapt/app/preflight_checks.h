#ifndef coulomb_adapt_app_preflight_checks_h
#define coulomb_adapt_app_preflight_checks_h

#include <deal.II/base/conditional_ostream.h>

#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/scene.h>

#include <string>

namespace coulomb_adapt
{
  /**
   * What the program refuses before any mesh is built (ParameterError,
   * naming the entry to change): degenerate cells in the scene's coarse
   * meshes, a body of a single cell (a blind zz/spr indicator), a body 1
   * more than 1e8 times stiffer than body 2, and first meshes above
   * 'Adaptation/Maximum number of DoFs' (estimated from the coarse
   * meshes). Nearly incompressible bodies with P1 elements get a warning
   * on @p pcout. @p mesh_source names where the meshes come from in
   * messages ("gmsh file 'x.msh': "; empty for the built-in scenes).
   */
  void
  check_before_meshing(const Scene              &scene,
                       const Parameters         &parameters,
                       const std::string        &mesh_source,
                       const ConditionalOStream &pcout);
} // namespace coulomb_adapt

#endif
