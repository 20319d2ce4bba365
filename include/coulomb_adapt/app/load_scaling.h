#ifndef coulomb_adapt_app_load_scaling_h
#define coulomb_adapt_app_load_scaling_h

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/scenes/scene.h>

#include <array>
#include <memory>
#include <string>

namespace coulomb_adapt
{
  /**
   * The stress scale of a scene's loads on the bodies' meshes: the
   * largest traction (MPa), body force times the body's size, and
   * Young's modulus times prescribed displacement over the body's size,
   * over every load step and both bodies, with where it is reached.
   */
  struct LoadStressScale
  {
    double stress = 0;
    /** E.g. "the traction on boundary part 2 of body 1 (upper block)". */
    std::string where;
    /** The larger side of the bodies' bounding boxes (mm). */
    double size = 0;
  };

  /** Evaluates the loads of @p bodies' descriptions at the nodes and face
   * and cell centres of their meshes; @p scene steps through its load
   * path (left at step 1). Collective. */
  LoadStressScale
  load_stress_scale(const Scene                                       &scene,
                    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies);

  /** The largest |initial gap| (mm, clearance or overlap) where the
   * contact curves of @p bodies face each other, as the mortar interface
   * measures it (the bodies' DoFs must be set up). Collective. */
  double
  largest_initial_gap(
    const std::array<std::unique_ptr<ElasticBody>, 2> &bodies);
} // namespace coulomb_adapt

#endif
