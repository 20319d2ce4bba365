#ifndef coulomb_adapt_scenes_manufactured_h
#define coulomb_adapt_scenes_manufactured_h

#include <coulomb_adapt/core/elastic_material.h>
#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * The smooth displacement field used for verification,
     *
     *   u = A (sin kx cos ky, cos kx sin ky) + B (sin kx cos ky, -cos kx sin
     * ky)
     *
     * with k = pi: a gradient part (A) and a divergence-free part (B), so
     * that the body force -div sigma(u) = 2k^2 [(lambda + 2 mu) A u_A +
     * mu B u_B] involves both Lamé parameters separately.
     */
    class ManufacturedDisplacement : public Function<2>
    {
    public:
      ManufacturedDisplacement(const double amplitude);

      double
      value(const Point<2> &p, const unsigned int component) const override;

      Tensor<1, 2>
      gradient(const Point<2> &p, const unsigned int component) const override;

      /** -div sigma(u) for the given material (N/mm^3). */
      Tensor<1, 2>
      body_force(const Point<2> &p, const ElasticMaterial &material) const;

      /** sigma(u) (MPa). */
      SymmetricTensor<2, 2>
      stress(const Point<2> &p, const ElasticMaterial &material) const;

    private:
      const double gradient_amplitude;
      const double rotational_amplitude;
    };



    /**
     * Two elastic bodies with the manufactured solution above and no
     * contact: [0,1] x [1,2] above [0,1] x [0,1], each with the exact
     * displacement on its left, right and bottom sides and the exact
     * traction sigma(u) n on its top side. The two-body elasticity demo and
     * the convergence tests run on it.
     */
    class Manufactured : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      Manufactured(ParameterHandler &prm, const PlaneModel plane_model);

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
      std::vector<unsigned int>                 subdivisions[2];
      std::array<MaterialConstants, 2>          materials;
      PlaneModel                                plane_model;
      std::shared_ptr<ManufacturedDisplacement> exact;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
