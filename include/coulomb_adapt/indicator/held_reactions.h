#ifndef coulomb_adapt_indicator_held_reactions_h
#define coulomb_adapt_indicator_held_reactions_h

#include <coulomb_adapt/indicator/equilibration_mesh.h>
#include <coulomb_adapt/scenes/scene.h>

#include <vector>

namespace coulomb_adapt
{
  namespace equilibration
  {
    /**
     * The reaction of the nodes that the scene's point constraints hold
     * ('Hold centre line', 'Hold axis': u_x = 0 on a line of nodes through
     * the body), carried by the equilibrated stress.
     *
     * Where the mesh is not symmetric about the line, the FE solution has a
     * nodal reaction R_k there: the residuals of the cells around node k
     * do not sum to its boundary loads, and the node systems could not be
     * solved (before: defects of 1e-4 to 1e-2 on remeshed punch and hertz,
     * and a sigma^ that was not statically admissible). The held line is a
     * support inside the body, so sigma^ n may jump across it in the held
     * component: each face of the line gets a traction g, carried by both
     * its cells (the jump is 2 g), with moments int g phi_k = w R_k / 2 at
     * its held nodes, w the face's share of node k's held faces (their
     * lengths). The moments are subtracted from the cells' residuals, so
     * that the node systems see every cell's whole load.
     *
     * Only faces inside the body whose nodes are all held carry g; a
     * held node on a Dirichlet face needs none, and an isolated held node
     * (a point support) has no face to carry it: its reaction stays in
     * the defects. Call after the prescribed and contact moments are set,
     * before the node systems.
     *
     * Returns the largest reaction of a held node (of a locally owned
     * cell) that no held face carries, relative to the largest cell
     * residual (as the node systems' defect): 0 where every held node lies
     * on a held line or a Dirichlet face.
     */
    double
    carry_held_reactions(const BodyDescription &description,
                         std::vector<CellData> &cells,
                         std::vector<FaceData> &faces);
  } // namespace equilibration
} // namespace coulomb_adapt

#endif
