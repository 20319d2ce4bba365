#ifndef coulomb_adapt_scenes_gmsh_bodies_h
#define coulomb_adapt_scenes_gmsh_bodies_h

#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  namespace gmsh_model
  {
    /** A mesh line by its two node tags, the smaller first. */
    using Edge = std::pair<std::size_t, std::size_t>;

    /**
     * The two bodies of a gmsh file, read with gmsh (on one rank) and
     * checked: the nodes (in the x-y plane), the circle arcs and the
     * other smooth curves (sampled) of the geometry, the physical groups and
     * each body's elements (from the surfaces GmshGroupUse::body_surfaces
     * names, none in both bodies). The curve groups are then looked up through
     * it: the contact pair and the condition groups (gmsh_two_body_reader.cc).
     * Errors are ParameterErrors that name the file, the group and the entry.
     */
    class GmshBodies
    {
    public:
      /** A mesh line with the gmsh curve it comes from. */
      using Lines = std::vector<std::pair<Edge, int>>;

      /** Open @p file_name in gmsh (which must be initialised; a .geo
       * file is meshed with @p mesh_size_factor, in quadrangles if
       * @p requested_cell_type asks for them) and read the bodies. */
      GmshBodies(const std::string  &file_name,
                 const GmshGroupUse &use,
                 const CellType      requested_cell_type,
                 const double        mesh_size_factor);

      /** The entities of physical group @p name, which @p entry names and
       * which must have dimension @p dim (@p why says why, for the
       * message). */
      std::vector<int>
      entities_of(const std::string &name,
                  const int          dim,
                  const std::string &entry,
                  const std::string &why) const;

      /** The lines of the curve group @p name, with the curve each comes
       * from. */
      Lines
      lines_of(const std::string &name,
               const std::string &entry,
               const std::string &why) const;

      /** How many of @p lines lie on the boundary of body @p b. */
      unsigned int
      count_on(const Lines &lines, const unsigned int b) const;

      const std::string file_name;
      /** "gmsh file 'name'", for messages. */
      const std::string in_file;

      std::map<std::size_t, Point<2>>            nodes;
      std::map<Edge, types::manifold_id>         curved_edges;
      CircleCentres                              circle_centres;
      SampledCurves                              sampled_curves;
      std::map<std::string, std::pair<int, int>> groups;
      /** Each body's elements as corner node tags, and its boundary. */
      std::array<std::vector<std::vector<std::size_t>>, 2> body_elements;
      std::array<std::set<Edge>, 2>                        body_boundary;

    private:
      void
      open(const CellType requested_cell_type,
           const double   mesh_size_factor) const;
      void
      check_two_dimensional() const;
      void
      read_nodes();
      void
      read_circle_arcs();
      void
      read_sampled_curves();
      void
      read_bodies(const GmshGroupUse &use);
      void
      require_known_nodes(const std::vector<std::vector<std::size_t>> &elements,
                          const std::string &what) const;

      /** The largest |coordinate|, the scale of the tolerances. */
      double extent = 0;
    };
  } // namespace gmsh_model
} // namespace coulomb_adapt

#endif
