#ifndef coulomb_adapt_scenes_gmsh_file_h
#define coulomb_adapt_scenes_gmsh_file_h

#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene.h>

#include <map>
#include <memory>
#include <optional>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * Any two-body geometry from a gmsh `.geo` or `.msh` file, with boundary
     * conditions and loads given per physical group (in the manner of
     * ASPECT's `Prescribed velocity boundary indicators`): fixed
     * components with optional prescribed values, tractions, normal
     * pressures and tangential tractions per curve group, the contact pair
     * (slave group, master group), and per body its surfaces, material and body
     * force (gravity, centrifugal). doc/scenes.md describes the entries.
     *
     * Without any of `Fixed components`, `Prescribed rotations`,
     * `Tractions`, `Normal pressures`, `Tangential tractions` the old
     * fixed groups apply:
     * `dirichlet` clamped, the uniform `Traction` on `traction`, contact
     * on `contact`.
     */
    class GmshFile : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      /** @p max_dofs, @p degree, @p global_refinements: a .geo file whose
       * meshes would have more DoFs than @p max_dofs is refused before it
       * is meshed (check_mesh_size_before_meshing()). */
      GmshFile(ParameterHandler  &prm,
               const PlaneModel   plane_model,
               const CellType     requested_cell_type,
               const double       max_dofs           = 0,
               const unsigned int degree             = 1,
               const unsigned int global_refinements = 0);

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

      std::string
      mesh_source() const override;

      /** `Load steps`: 1 is the static problem. */
      unsigned int
      n_load_steps() const override;

      /** Step @p step of n carries the fraction step/n of every
       * prescribed value and load (the initial overlap is geometry: all
       * of it from step 1). */
      void
      set_load_step(const unsigned int step) const override;

      /** The same scene with a .geo file meshed at 2^k times its
       * `Mesh size factor` (every size of the file's size field scaled
       * alike): the coarser meshes of the nested iteration. None for a
       * .msh file, which brings its own mesh. */
      std::unique_ptr<Scene>
      with_coarser_graded_meshes(const unsigned int k) const override;

      bool
      coarser_meshes_scale_every_size() const override
      {
        return true;
      }

      /** What applies on the curves of one physical group. */
      struct GroupConditions
      {
        /** Prescribed displacement (mm) of x and y, where fixed. */
        std::array<std::optional<double>, 2> fixed;
        /** Prescribed rigid rotation (rad) about the rotation centre,
         * linearised: u = angle (-(y - c_y), x - c_x), both components. */
        std::optional<double> rotation;
        /** Traction vector (MPa). */
        Tensor<1, 2> traction;
        /** Normal pressure (MPa): the traction -p n. */
        double pressure = 0;
        /** Tangential traction (MPa): the traction s t along the
         * boundary's tangent t = (-n_y, n_x) (n turned counterclockwise). */
        double shear = 0;
        /** Whether any traction, pressure or tangential traction is
         * given. */
        bool loaded = false;
      };

      /** Constant and centrifugal body force of one body. */
      struct BodyForce
      {
        /** Mass density (t/mm^3, so that density x acceleration is in
         * N/mm^3). */
        double density = 0;
        /** Acceleration of gravity (mm/s^2). */
        Tensor<1, 2> gravity;
        /** Angular velocity (rad/s) about the axis through
         * @p axis perpendicular to the plane. */
        double   angular_velocity = 0;
        Point<2> axis;
      };

    private:
      /** Refuse a .geo file whose meshes at 'Mesh size factor' would have
       * more than @p max_dofs DoFs (0: no limit), from probes meshed
       * 2^k times coarser. */
      void
      check_mesh_size_before_meshing(
        const double       max_dofs,
        const unsigned int degree,
        const unsigned int global_refinements) const;
      /** Body @p b's surfaces (into @p use) and body force. */
      void
      parse_body(ParameterHandler  &prm,
                 const unsigned int b,
                 GmshGroupUse      &use);
      /** The conditions per group and the groups of @p use they name. */
      void
      parse_conditions(ParameterHandler &prm, GmshGroupUse &use);
      void
      parse_condition_entries(ParameterHandler &prm, GmshGroupUse &use);
      /** Checks of the conditions against the file's groups, once read. */
      void
      check_point_supports();
      void
      check_shared_groups();

      std::string       mesh_file;
      CellType          requested_cell_type;
      double            size_factor = 1;
      GmshGroupUse      group_use;
      TwoBodyGmshMeshes geometry;
      /** The coarser meshings (with_coarser_graded_meshes()) by k, meshed
       * once: the driver asks for k = 1 before it uses it. */
      mutable std::map<unsigned int, std::shared_ptr<const TwoBodyGmshMeshes>>
                                             coarser_geometries;
      std::map<std::string, GroupConditions> conditions;
      std::array<MaterialConstants, 2>       materials;
      std::array<BodyForce, 2>               body_forces;
      /** The centre of the prescribed rotations (mm). */
      Point<2>     rotation_centre;
      unsigned int n_steps = 1;
      /** The fraction of the prescribed values and loads in the current
       * load step (set_load_step). */
      mutable double load_fraction = 1;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
