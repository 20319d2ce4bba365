#ifndef coulomb_adapt_scenes_gmsh_file_h
#define coulomb_adapt_scenes_gmsh_file_h

#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene.h>

namespace coulomb_adapt
{
  namespace scenes
  {
    /**
     * Any two-body geometry from a gmsh `.geo` or `.msh` file (see
     * read_two_body_gmsh_file for the physical groups it must define):
     * clamped on `dirichlet`, a uniform traction on `traction`, contact
     * candidate `contact`.
     */
    class GmshFile : public Scene
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      GmshFile(ParameterHandler &prm,
               const PlaneModel  plane_model,
               const CellType    requested_cell_type);

      std::string
      name() const override;

      void
      create_coarse_mesh(const unsigned int body,
                         const CellType     cell_type,
                         Triangulation<2> & tria) const override;

      BodyDescription
      describe_body(const unsigned int body) const override;

    private:
      std::array<CoarseMeshData, 2> meshes;
      Tensor<1, 2>                  traction;
      std::array<MaterialConstants, 2>             materials;
    };
  } // namespace scenes
} // namespace coulomb_adapt

#endif
