#ifndef coulomb_adapt_scenes_patch_h
#define coulomb_adapt_scenes_patch_h

#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * Contact patch test (theory.md section 6): two blocks of equal width
     * stacked, uniform pressure p on top of the upper one, the lower one on
     * rollers at its base with its lower left corner fixed. The exact
     * stress is uniform, sigma_yy = -p, for any (non-matching) meshes.
     * Upper block [0,W] x [H2, H2+H1], lower block [0,W] x [0,H2].
     */
    class Patch : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      Patch(ParameterHandler &prm, const PlaneModel plane_model);

      std::string
      name() const override;

      std::vector<std::string>
      load_entries() const override;

      void
      create_coarse_mesh(const unsigned int body,
                         const CellType     cell_type,
                         Triangulation<2>  &tria) const override;

      BodyDescription
      describe_body(const unsigned int body) const override;

    private:
      double                           width;
      double                           heights[2];
      std::vector<unsigned int>        subdivisions[2];
      double                           pressure;
      bool                             hold_upper_body;
      double                           shear_traction;
      std::array<MaterialConstants, 2> materials;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
