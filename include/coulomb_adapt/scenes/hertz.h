#ifndef coulomb_adapt_scenes_hertz_h
#define coulomb_adapt_scenes_hertz_h

#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * Hertz line contact (theory.md section 6): the lower half of a disc of
     * radius R, centre (0, R), loaded by a uniform traction on its flat top
     * (total P' per unit thickness), resting on the block [-L, L] x [-H, 0]
     * clamped at its base. First contact at the origin. The meshes are
     * refined towards the origin so that the contact half-width
     * a = sqrt(4 P' R / (pi E*)) is resolved; keep a << R, L, H.
     */
    class Hertz : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      Hertz(ParameterHandler &prm, const PlaneModel plane_model);

      std::string
      name() const override;

      void
      create_coarse_mesh(const unsigned int body,
                         const CellType     cell_type,
                         Triangulation<2> & tria) const override;

      void
      refine_initial_mesh(const unsigned int body,
                          Triangulation<2> & tria) const override;

      BodyDescription
      describe_body(const unsigned int body) const override;

      /** Hertz's contact half-width a (mm). */
      double
      contact_half_width() const;

      /** Hertz's peak pressure p0 = 2 P' / (pi a) (MPa). */
      double
      peak_pressure() const;

    private:
      double                    radius;
      double                    line_load;
      double                    block_width, block_height;
      std::vector<unsigned int> block_subdivisions;
      unsigned int              contact_refinements;
      double                    refined_zone_factor;
      PlaneModel                plane_model;
      MaterialConstants         materials[2];
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
