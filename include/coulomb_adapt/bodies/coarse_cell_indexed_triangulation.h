#ifndef coulomb_adapt_bodies_coarse_cell_indexed_triangulation_h
#define coulomb_adapt_bodies_coarse_cell_indexed_triangulation_h

#include <deal.II/distributed/fully_distributed_tria.h>

#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * A parallel::fullydistributed::Triangulation whose coarse cell id ->
   * coarse cell index lookup is a table instead of deal.II's binary search.
   *
   * deal.II 9.4's create_triangulation() from a description sorts the cell
   * infos with a comparison that looks up both cells' coarse cell indices;
   * with one coarse cell per triangle (a remeshed body) that sort made
   * about a third of the remeshing time of an adaptive run
   * (benchmarks/adaptive_run/README.md). The table gives the same index
   * for every id, so the triangulation is the one deal.II builds.
   */
  class CoarseCellIndexedTriangulation
    : public parallel::fullydistributed::Triangulation<2>
  {
  public:
    using parallel::fullydistributed::Triangulation<2>::Triangulation;
    using parallel::fullydistributed::Triangulation<2>::create_triangulation;

    void
    create_triangulation(
      const TriangulationDescription::Description<2, 2> &description) override;

  private:
    // Private in deal.II's class too.
    unsigned int
    coarse_cell_id_to_coarse_cell_index(
      const types::coarse_cell_id coarse_cell_id) const override;

    // index_of_id[id]: the coarse cell index of coarse cell id 'id', or
    // numbers::invalid_unsigned_int.
    std::vector<unsigned int> index_of_id;
  };
} // namespace coulomb_adapt

#endif
