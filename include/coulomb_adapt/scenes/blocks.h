#ifndef coulomb_adapt_scenes_blocks_h
#define coulomb_adapt_scenes_blocks_h

#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * The seed's example (theory.md section 5): a 100 x 100 mm block
     * Omega^1 = [50,150] x [200,300] pressed by a uniform traction on its
     * top onto a 200 x 200 mm block Omega^2 = [0,200] x [0,200] clamped at
     * y = 0. Contact candidate: y = 200. Omega^1 has no support besides
     * contact unless its centre line x = 100 is held horizontally.
     */
    class Blocks : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      Blocks(ParameterHandler &prm, const PlaneModel plane_model);

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
      std::vector<unsigned int>        upper_subdivisions;
      std::vector<unsigned int>        lower_subdivisions;
      double                           pressure;
      bool                             hold_centre_line;
      std::array<MaterialConstants, 2> materials;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
