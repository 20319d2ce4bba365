#include <coulomb_adapt/bodies/coarse_cell_indexed_triangulation.h>

#include <algorithm>
#include <string>

namespace coulomb_adapt
{
  void
  CoarseCellIndexedTriangulation::create_triangulation(
    const TriangulationDescription::Description<2, 2> &description)
  {
    // The ids are the serial mesh's cell indices: the table has as many
    // entries as that mesh has cells (4 bytes each), on every rank.
    const auto &ids = description.coarse_cell_index_to_coarse_cell_id;
    index_of_id.clear();
    if (!ids.empty())
      {
        index_of_id.assign(*std::max_element(ids.begin(), ids.end()) + 1,
                           numbers::invalid_unsigned_int);
        for (unsigned int i = 0; i < ids.size(); ++i)
          index_of_id[ids[i]] = i;
      }
    parallel::fullydistributed::Triangulation<2>::create_triangulation(
      description);
  }



  // deal.II's lookup (a lower bound in the sorted ids) gives, for an id
  // that is not there, the index of the next larger one; a description
  // without cells leaves deal.II one dummy cell, index 0. Both are kept.
  unsigned int
  CoarseCellIndexedTriangulation::coarse_cell_id_to_coarse_cell_index(
    const types::coarse_cell_id coarse_cell_id) const
  {
    if (index_of_id.empty())
      return 0;
    for (types::coarse_cell_id id = coarse_cell_id; id < index_of_id.size();
         ++id)
      if (index_of_id[id] != numbers::invalid_unsigned_int)
        return index_of_id[id];
    AssertThrow(false,
                ExcMessage("coarse cell id " + std::to_string(coarse_cell_id) +
                           " is not a coarse cell of this mesh"));
    return numbers::invalid_unsigned_int;
  }
} // namespace coulomb_adapt
