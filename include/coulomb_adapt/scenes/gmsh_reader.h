#ifndef coulomb_adapt_scenes_gmsh_reader_h
#define coulomb_adapt_scenes_gmsh_reader_h

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/curve_manifold.h>

#include <array>
#include <map>
#include <set>
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
   * One body's mesh from gmsh elements (corner node tags, triangles or
   * quadrangles, either orientation) and the boundary lines of each
   * boundary id; only lines that are boundary edges of these elements are
   * kept. @p file_name is for messages. A boundary edge in
   * @p curved_edges (an edge of two node tags, the smaller first) lies on a
   * circle or another smooth curve of the geometry and gets its manifold
   * id, with boundary id 0
   * (free) if no group names it.
   */
  CoarseMeshData
  build_body_mesh(const std::vector<std::vector<std::size_t>> &elements,
                  const std::map<std::size_t, Point<2>>       &all_nodes,
                  const std::map<types::boundary_id,
                                 std::vector<std::vector<std::size_t>>> &lines,
                  const types::material_id            material_id,
                  const std::string                  &file_name,
                  const std::map<std::pair<std::size_t, std::size_t>,
                                 types::manifold_id> &curved_edges = {});

  /** The centres of the circles of a gmsh geometry, by the manifold id
   * that the boundary lines on them carry. */
  using CircleCentres = std::map<types::manifold_id, Point<2>>;

  /** Attach a SphericalManifold with each centre of @p centres to its
   * manifold id in @p tria. */
  void
  attach_circle_manifolds(const CircleCentres &centres, Triangulation<2> &tria);

  /**
   * The physical groups of a gmsh file that the gmsh scene uses, and what
   * for: read_two_body_gmsh_geometry() checks them against the file and
   * gives every boundary line its boundary id. Entries name the parameter
   * that names a group, for messages.
   */
  struct GmshGroupUse
  {
    /** The physical surfaces that form body 1 (upper, slave) and body 2. */
    std::array<std::vector<std::string>, 2> body_surfaces = {
      {{"body 1"}, {"body 2"}}};
    std::array<std::string, 2> body_entries = {
      {"Scene/Gmsh/Body 1/Physical surfaces",
       "Scene/Gmsh/Body 2/Physical surfaces"}};
    /** The slave group (its lines on body 1's boundary) and the master
     * group (on body 2's); one group may serve as both, its lines then
     * split by the body they bound. */
    std::array<std::string, 2> contact_pair  = {{"contact", "contact"}};
    std::string                contact_entry = "Scene/Gmsh/Contact pair";
    /** Curve groups with boundary conditions or loads, in the order of the
     * entries, each with the entry that names it first. */
    std::vector<std::pair<std::string, std::string>> condition_groups = {
      {"dirichlet", "Scene/Gmsh (the old 'dirichlet' group)"},
      {"traction", "Scene/Gmsh/Traction"}};
    /** Those that clamp both components to zero: they share
     * boundary_ids::dirichlet, the id the mesh adaptation knows as a
     * support, and a curve in one of them takes no other condition. */
    std::set<std::string> clamped_groups = {"dirichlet"};
    /** Condition groups that may be physical points (point supports). */
    std::set<std::string> point_groups_allowed;
  };

  /**
   * The two bodies' coarse meshes of a gmsh file and what their boundary
   * ids stand for. The contact lines have boundary_ids::contact; the lines
   * of the condition groups have boundary_ids::dirichlet if all their
   * groups clamp, otherwise one id (from 3 up) per set of groups a line
   * belongs to.
   */
  struct TwoBodyGmshMeshes
  {
    std::array<CoarseMeshData, 2> meshes;
    /** The condition groups on the lines of each boundary id. */
    std::map<types::boundary_id, std::vector<std::string>>
      groups_of_boundary_id;

    /** A node of a physical point group, in one body's mesh. */
    struct PointSupport
    {
      std::string  group;
      unsigned int body;
      Point<2>     position;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int)
      {
        archive &group &body &position;
      }
    };
    std::vector<PointSupport> point_supports;
    /** The circles of the geometry: the boundary lines on one have its
     * manifold id (attach_circle_manifolds() gives the manifolds). */
    CircleCentres circle_centres;
    /** The other smooth curves of the geometry (splines, B-splines, Bezier
     * curves, ellipses), sampled: the boundary lines on one have its
     * manifold id (attach_curve_manifolds() gives the manifolds). */
    SampledCurves sampled_curves;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &meshes &groups_of_boundary_id &point_supports &circle_centres
        &sampled_curves;
    }
  };

  /**
   * Read a two-body geometry through the gmsh API. A `.msh` file is read
   * as it is; a `.geo` file is meshed first (triangles, or quadrilaterals
   * by recombination when @p requested_cell_type asks for them), with
   * element sizes scaled by @p mesh_size_factor. Only the corner nodes of
   * higher-order gmsh elements are used; any boundary that no group of
   * @p use names is free (boundary id 0).
   *
   * The file is read on rank 0 of @p comm and the meshes given to every
   * rank, with the groups of @p use. Errors, gmsh's own (a syntax error in a .geo
   * file, a truncated or inconsistent .msh file) included, throw a
   * ParameterError on every rank that names the file and says what is
   * wrong: a group that the file lacks or that has the wrong dimension,
   * duplicate physical names, a surface in both bodies, a curve that is
   * both a contact curve and carries a condition, a condition group off
   * the bodies' boundaries, a contact pair that is not body 1 against
   * body 2, a 3D mesh or nodes off the x-y plane.
   */
  TwoBodyGmshMeshes
  read_two_body_gmsh_geometry(const std::string  &file_name,
                              const CellType      requested_cell_type,
                              const double        mesh_size_factor,
                              const GmshGroupUse &use,
                              const MPI_Comm      comm = MPI_COMM_SELF);

  /**
   * The same with the old fixed groups (GmshGroupUse's defaults): surfaces
   * `body 1`, `body 2`, curves `dirichlet`, `traction`, `contact`.
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
