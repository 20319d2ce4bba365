#ifndef coulomb_adapt_scenes_gmsh_model_h
#define coulomb_adapt_scenes_gmsh_model_h

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Queries of the model that gmsh has open (gmsh_bodies.cc and
   * gmsh_two_body_reader.cc read the bodies and groups of a two-body file
   * with them). Errors name the file
   * @p file_name.
   */
  namespace gmsh_model
  {
    /** Corner nodes of a gmsh element type that is accepted (lines,
     * triangles, quadrangles of any order); 0 for the others. */
    unsigned int
    n_corners(const int gmsh_element_type);

    /** "point", "curve", "surface" or "volume". */
    const char *
    dimension_name(const int dim);

    /** Every physical group of the open model by name: (dimension, tag).
     * Two groups of one name are an error. */
    std::map<std::string, std::pair<int, int>>
    physical_groups_by_name(const std::string &file_name);

    /** The groups for a message: "surface 'a', curve 'b'", or "none". */
    std::string
    list_of_groups(const std::map<std::string, std::pair<int, int>> &groups);

    /** Corner node tags of the elements of the entities @p entities of
     * dimension @p dim, each entity once. */
    std::vector<std::vector<std::size_t>>
    elements_of_entities(const int               dim,
                         const std::vector<int> &entities,
                         const std::string      &file_name);
  } // namespace gmsh_model
} // namespace coulomb_adapt

#endif
