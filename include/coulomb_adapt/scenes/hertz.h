#ifndef coulomb_adapt_scenes_hertz_h
#define coulomb_adapt_scenes_hertz_h

#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene.h>

#include <memory>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * Hertz line contact (theory.md section 6): the lower half of a disc of
     * radius R, centre (0, R), loaded by a uniform traction on its flat top
     * (total P' per unit thickness), resting on the block [-L, L] x [-H, 0]
     * clamped at its base. First contact at the origin. The meshes are
     * graded towards the origin so that the contact half-width
     * a = sqrt(4 P' R / (pi E*)) is resolved (`Contact mesh size`):
     * quadrilaterals by local refinement (hanging nodes), triangles by a
     * gmsh size field. Keep a << R, L, H.
     *
     * The scene `cattaneo` (Cattaneo-Mindlin) is this geometry loaded
     * through a rigid holder on the disc's top (which keeps the disc from
     * rotating): load step 1 pushes it down, steps 2 ... N+1 move it
     * sideways. P' and Q are the resulting contact force; for Q < mu P' the
     * stick zone shrinks to |x| < c = a sqrt(1 - Q / (mu P')).
     */
    class Hertz : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      /** With @p cattaneo, the scene `cattaneo`: the same geometry, then a
       * tangential load after the normal one (subsection `Cattaneo`).
       * @p parameters: the cell type, degree and global refinements of the
       * first meshes, and the DoF limit they must keep to (a `Contact mesh
       * size` whose meshes would exceed it is refused before meshing). */
      Hertz(ParameterHandler &prm,
            const Parameters &parameters,
            const bool        cattaneo = false);

      std::string
      name() const override;

      std::vector<std::string>
      load_entries() const override;

      void
      create_coarse_mesh(const unsigned int body,
                         const CellType     cell_type,
                         Triangulation<2>  &tria) const override;

      void
      refine_initial_mesh(const unsigned int body,
                          Triangulation<2>  &tria) const override;

      BodyDescription
      describe_body(const unsigned int body) const override;

      /** hertz_half_width a, hertz_peak_pressure p0, line_load P',
       * radius R, friction_coefficient is not known here. */
      std::map<std::string, double>
      reference_values() const override;

      unsigned int
      n_load_steps() const override;

      void
      set_load_step(const unsigned int step) const override;

      /** cattaneo: 1 from step 3 on (equal tangential increments); step 2,
       * the first tangential one, follows the normal step. */
      double
      load_increment_ratio(const unsigned int step) const override;

      /** The same contact with `Contact mesh size` times 2^k (its own
       * gmsh meshes). */
      std::unique_ptr<Scene>
      with_coarser_graded_meshes(const unsigned int k) const override;

      /** Hertz's contact half-width a (mm). */
      double
      contact_half_width() const;

      /** Target element size near the first contact point (mm). */
      double
      contact_mesh_size() const;

      /** Hertz's peak pressure p0 = 2 P' / (pi a) (MPa). */
      double
      peak_pressure() const;

    private:
      /** Refuse a `Contact mesh size` whose graded meshes would exceed
       * `Adaptation/Maximum number of DoFs`, or, 0 with quadrilaterals
       * and no global refinement, would leave the disc's 4 coarse cells. */
      void
      check_initial_mesh_size(const Parameters &parameters) const;

      /** Both bodies meshed by gmsh with triangles (made once). */
      const std::array<CoarseMeshData, 2> &
      triangle_meshes() const;

      mutable std::shared_ptr<std::array<CoarseMeshData, 2>> gmsh_meshes;
      double                                                 radius;
      double                                                 line_load;
      bool                                                   hold_axis;
      bool                                                   cattaneo;
      double       normal_displacement;
      double       tangential_displacement;
      unsigned int n_tangential_steps;
      /** Fraction of the tangential displacement applied in this step. */
      mutable double                   tangential_fraction = 0;
      double                           block_width, block_height;
      std::vector<unsigned int>        block_subdivisions;
      double                           contact_mesh_factor;
      double                           refined_zone_factor;
      PlaneModel                       plane_model;
      std::array<MaterialConstants, 2> materials;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
