#ifndef coulomb_adapt_scenes_scaled_scene_h
#define coulomb_adapt_scenes_scaled_scene_h

#include <coulomb_adapt/core/units.h>
#include <coulomb_adapt/scenes/scene.h>

#include <memory>

namespace coulomb_adapt
{
  /**
   * A scene with every load divided by the load scale P (core/units.h):
   * tractions, body forces, prescribed displacements and the exact
   * displacement, on every load step and on the coarser graded meshes of
   * nested iteration. Geometry is the scene's own. With a displacement
   * scale D other than P (set_scales: extreme moduli, or a gap),
   * tractions and body forces are divided by P, prescribed and exact
   * displacements by D, Young's moduli by P / D.
   *
   * The functions of describe_body() read P when they are evaluated, so
   * P may be chosen after the bodies are made (from their meshes and
   * loads); set it before the first assembly. With P = 1 every load is
   * the scene's own to the last bit.
   */
  class ScaledScene : public Scene
  {
  public:
    explicit ScaledScene(std::unique_ptr<Scene> scene);

    /** The load scale P (> 0, a power of 2). */
    void
    set_load_scale(const double load_scale);

    double
    load_scale() const;

    /** P and D (units::Scales); set_load_scale(P) means D = P. */
    void
    set_scales(const units::Scales &scales);

    units::Scales
    scales() const;

    std::string
    name() const override;

    void
    create_coarse_mesh(const unsigned int body,
                       const CellType     cell_type,
                       Triangulation<2>  &tria) const override;

    void
    refine_initial_mesh(const unsigned int body,
                        Triangulation<2>  &tria) const override;

    BodyDescription
    describe_body(const unsigned int body) const override;

    std::string
    mesh_source() const override;

    std::map<std::string, double>
    reference_values() const override;

    std::vector<std::string>
    load_entries() const override;

    unsigned int
    n_load_steps() const override;

    void
    set_load_step(const unsigned int step) const override;

    double
    load_increment_ratio(const unsigned int step) const override;

    std::unique_ptr<Scene>
    with_coarser_graded_meshes(const unsigned int k) const override;

    bool
    coarser_meshes_scale_every_size() const override;

  private:
    ScaledScene(std::unique_ptr<Scene>  scene,
                std::shared_ptr<double> load_scale,
                std::shared_ptr<double> displacement_scale);

    std::unique_ptr<Scene> scene;
    /** Shared with the functions handed out and with the coarser scenes. */
    std::shared_ptr<double> scale;
    /** D: divides the prescribed and exact displacements (shared too). */
    std::shared_ptr<double> displacement_scale;
  };
} // namespace coulomb_adapt

#endif
