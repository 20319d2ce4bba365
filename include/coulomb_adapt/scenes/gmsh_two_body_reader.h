#ifndef coulomb_adapt_scenes_gmsh_two_body_reader_h
#define coulomb_adapt_scenes_gmsh_two_body_reader_h

#include <coulomb_adapt/scenes/gmsh_reader.h>

#include <string>

namespace coulomb_adapt
{
  /**
   * Open @p file_name in gmsh (which must be initialised; a .geo file is
   * meshed with @p mesh_size_factor, in quadrangles if
   * @p requested_cell_type asks for them) and read the two bodies, the
   * contact pair and the condition groups that @p use names, each checked
   * against the file: a ParameterError names the first thing wrong. Runs
   * on one rank; read_two_body_gmsh_geometry() calls it there and
   * broadcasts the result.
   */
  TwoBodyGmshMeshes
  read_two_body_model(const std::string  &file_name,
                      const CellType      requested_cell_type,
                      const double        mesh_size_factor,
                      const GmshGroupUse &use);
} // namespace coulomb_adapt

#endif
