#ifndef coulomb_adapt_indicator_equilibration_node_systems_h
#define coulomb_adapt_indicator_equilibration_node_systems_h

#include <coulomb_adapt/indicator/equilibrated_stress.h>
#include <coulomb_adapt/indicator/equilibration_mesh.h>

#include <vector>

namespace coulomb_adapt
{
  namespace equilibration
  {
    /** Step 3: the node systems of every node of a locally owned cell,
     * in least squares closest to the averaged moments; the moments of the
     * faces are set, and the free parameter of each system (its null
     * vector) is stored in FaceData::kernel. */
    void
    solve_node_systems(const std::vector<CellData> &cells,
                       std::vector<FaceData>       &faces,
                       const unsigned int           n_nodes,
                       EquilibratedStressErrors    &result);
  } // namespace equilibration
} // namespace coulomb_adapt

#endif
