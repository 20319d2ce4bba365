#include <coulomb_adapt/output/vtu_pieces.h>

#include <iterator>

namespace coulomb_adapt
{
  VtuPieces
  DataOutInPieces::take_pieces(const unsigned int max_cells)
  {
    const std::size_t n_cells  = patches.size();
    const std::size_t n_pieces = (max_cells == 0 || n_cells <= max_cells) ?
                                   1 :
                                   (n_cells + max_cells - 1) / max_cells;
    VtuPieces         pieces;
    pieces.names            = get_dataset_names();
    pieces.nonscalar_ranges = get_nonscalar_data_ranges();
    for (std::size_t p = 0; p < n_pieces; ++p)
      {
        const auto begin = patches.begin() + p * n_cells / n_pieces;
        const auto end   = patches.begin() + (p + 1) * n_cells / n_pieces;
        pieces.patches.emplace_back(std::make_move_iterator(begin),
                                    std::make_move_iterator(end));
      }
    patches.clear();
    return pieces;
  }
} // namespace coulomb_adapt
