#ifndef coulomb_adapt_scenes_gmsh_reader_h
#define coulomb_adapt_scenes_gmsh_reader_h

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <coulomb_adapt/core/parameters.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The coarse mesh of one body as read from a file: enough to create a
   * Triangulation any number of times.
   */
  struct CoarseMeshData
  {
    std::vector<Point<2>>    vertices;
    std::vector<CellData<2>> cells;
    SubCellData              boundary_lines;

    void
    create_triangulation(Triangulation<2> &tria) const;

    /** For the broadcast from the rank that read the file. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &vertices &cells &boundary_lines.boundary_lines;
    }
  };

  /**
   * Read a two-body geometry through the gmsh API. A `.msh` file is read
   * as it is; a `.geo` file is meshed first (triangles, or quadrilaterals
   * by recombination when @p requested_cell_type asks for them), with
   * element sizes scaled by @p mesh_size_factor.
   *
   * The file must name, as physical groups, the surfaces `body 1` (upper,
   * slave) and `body 2` (lower, master) and the curves `dirichlet`
   * (clamped), `traction` and `contact`; they get the boundary ids of
   * scene_meshes.h. Any other boundary is free. Only the corner nodes of
   * higher-order gmsh elements are used. Errors (missing file, missing
   * group, unsupported elements) name the file and what is missing.
   */
  /**
   * One body's mesh from gmsh elements (corner node tags, triangles or
   * quadrangles, either orientation) and the boundary lines of each
   * boundary id; only lines that are boundary edges of these elements are
   * kept. @p file_name is for messages.
   */
  CoarseMeshData
  build_body_mesh(
    const std::vector<std::vector<std::size_t>> &elements,
    const std::map<std::size_t, Point<2>> &      all_nodes,
    const std::map<types::boundary_id, std::vector<std::vector<std::size_t>>>
      &                      lines,
    const types::material_id material_id,
    const std::string &      file_name);

  /**
   * Read the file on rank 0 of @p comm and give the meshes to every rank.
   * Errors, gmsh's own (a syntax error in a .geo file, a truncated or
   * inconsistent .msh file) included, throw a ParameterError on every
   * rank that names the file and says what is wrong.
   */
  std::array<CoarseMeshData, 2>
  read_two_body_gmsh_file(const std::string &file_name,
                          const CellType     requested_cell_type,
                          const double       mesh_size_factor,
                          const MPI_Comm     comm = MPI_COMM_SELF);

  /**
   * gmsh's message for an error that its API threw (as the std::string
   * @p thrown, or as anything else with @p thrown empty): the last error
   * from gmsh's logger, else @p thrown. Call it before gmsh::finalize().
   */
  std::string
  gmsh_error_message(const std::string &thrown);
} // namespace coulomb_adapt

#endif
