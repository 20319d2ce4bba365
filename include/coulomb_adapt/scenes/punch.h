#ifndef coulomb_adapt_scenes_punch_h
#define coulomb_adapt_scenes_punch_h

#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * A stiff flat punch [-w/2, w/2] x [0, h] pressed by a uniform pressure
     * onto a block [-L, L] x [-H, 0] clamped at its base. The punch's
     * corners make the contact pressure singular: steep gradients for the
     * error indicator and the adaptation to find.
     */
    class Punch : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      Punch(ParameterHandler &prm, const PlaneModel plane_model);

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
      double                           punch_width, punch_height;
      double                           block_width, block_height;
      std::vector<unsigned int>        subdivisions[2];
      double                           pressure;
      bool                             hold_centre_line;
      std::array<MaterialConstants, 2> materials;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
