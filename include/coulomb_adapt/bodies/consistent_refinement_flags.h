#ifndef coulomb_adapt_bodies_consistent_refinement_flags_h
#define coulomb_adapt_bodies_consistent_refinement_flags_h

#include <deal.II/distributed/tria_base.h>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * prepare_coarsening_and_refinement() of a distributed mesh whose result
   * does not depend on the number of ranks: call it with the refine and
   * coarsen flags set on the locally owned cells.
   *
   * deal.II 9.4's parallel::distributed::Triangulation applies the serial
   * smoothing rules on each rank with the flags that rank sees. Its ghost
   * cells carry no flags, and a ghost's siblings are often artificial, so
   * a ghost family is never coarsened there; an owned family beside it was
   * then kept too (two levels apart at a vertex otherwise), and a Q2 punch
   * run refined on 2 ranks kept 54 cells more than on 1 rank. Here the
   * owners' flags are copied to the ghost cells, a family coarsened by its
   * owner is flagged on the ghost's artificial siblings too, and the rules
   * are applied again until no rank changes its own cells' flags.
   * execute_coarsening_and_refinement() clears the flags of cells a rank
   * does not own; p4est gets the owners' flags.
   */
  void
  prepare_refinement_flags_consistently(parallel::TriangulationBase<2> &tria);
} // namespace coulomb_adapt

#endif
