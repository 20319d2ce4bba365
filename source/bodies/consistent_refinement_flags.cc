#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <coulomb_adapt/bodies/consistent_refinement_flags.h>

#include <cstdint>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    constexpr std::uint8_t refine_bit = 1, coarsen_bit = 2;

    std::uint8_t
    flag_bits(const Triangulation<2>::active_cell_iterator &cell)
    {
      return (cell->refine_flag_set() ? refine_bit : 0) |
             (cell->coarsen_flag_set() ? coarsen_bit : 0);
    }



    // The owners' flags on this rank's ghost cells. A coarsen flag that
    // survived the owner's rules stands for the whole family (families are
    // never split between ranks): its artificial siblings get it too.
    void
    copy_owner_flags_to_ghosts(parallel::TriangulationBase<2> &tria)
    {
      std::vector<std::uint8_t> ghost_bits(tria.n_active_cells(), 0);
      GridTools::exchange_cell_data_to_ghosts<std::uint8_t, Triangulation<2>>(
        tria,
        [](const Triangulation<2>::active_cell_iterator &cell) {
          return flag_bits(cell);
        },
        [&](const Triangulation<2>::active_cell_iterator &cell,
            const std::uint8_t                            bits) {
          ghost_bits[cell->active_cell_index()] = bits;
        });

      for (const auto &cell : tria.active_cell_iterators())
        if (!cell->is_locally_owned())
          {
            cell->clear_refine_flag();
            cell->clear_coarsen_flag();
          }
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_ghost())
          {
            const std::uint8_t bits = ghost_bits[cell->active_cell_index()];
            if (bits & refine_bit)
              cell->set_refine_flag();
            if ((bits & coarsen_bit) && cell->level() > 0)
              for (const auto &sibling : cell->parent()->child_iterators())
                if (sibling->is_active() && !sibling->is_locally_owned() &&
                    !sibling->refine_flag_set())
                  sibling->set_coarsen_flag();
          }
    }



    std::vector<std::uint8_t>
    owned_flags(const parallel::TriangulationBase<2> &tria)
    {
      std::vector<std::uint8_t> bits;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          bits.push_back(flag_bits(cell));
      return bits;
    }
  } // namespace



  void
  prepare_refinement_flags_consistently(parallel::TriangulationBase<2> &tria)
  {
    // The rules only add refine flags and take coarsen flags away, so the
    // owned flags change finitely often.
    while (true)
      {
        copy_owner_flags_to_ghosts(tria);
        const std::vector<std::uint8_t> before = owned_flags(tria);
        tria.prepare_coarsening_and_refinement();
        const bool changed = owned_flags(tria) != before;
        if (!Utilities::MPI::logical_or(changed, tria.get_communicator()))
          break;
      }
  }
} // namespace coulomb_adapt
