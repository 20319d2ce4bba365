#include <coulomb_adapt/output/vtu_pieces.h>

#include <iterator>

namespace coulomb_adapt
{
  VtuPiece::VtuPiece(std::vector<Patch>       patches,
                     std::vector<std::string> names,
                     NonscalarRanges          nonscalar_ranges)
    : patches(std::move(patches))
    , names(std::move(names))
    , nonscalar_ranges(std::move(nonscalar_ranges))
  {}



  const std::vector<VtuPiece::Patch> &
  VtuPiece::get_patches() const
  {
    return patches;
  }



  std::vector<std::string>
  VtuPiece::get_dataset_names() const
  {
    return names;
  }



  VtuPiece::NonscalarRanges
  VtuPiece::get_nonscalar_data_ranges() const
  {
    return nonscalar_ranges;
  }



  std::vector<std::unique_ptr<VtuPiece>>
  DataOutInPieces::take_pieces(const unsigned int max_cells)
  {
    const std::size_t n_cells  = patches.size();
    const std::size_t n_pieces = (max_cells == 0 || n_cells <= max_cells) ?
                                   1 :
                                   (n_cells + max_cells - 1) / max_cells;
    const std::vector<std::string>  names  = get_dataset_names();
    const VtuPiece::NonscalarRanges ranges = get_nonscalar_data_ranges();

    std::vector<std::unique_ptr<VtuPiece>> pieces;
    for (std::size_t p = 0; p < n_pieces; ++p)
      {
        const auto begin = patches.begin() + p * n_cells / n_pieces;
        const auto end   = patches.begin() + (p + 1) * n_cells / n_pieces;
        pieces.push_back(std::make_unique<VtuPiece>(
          std::vector<VtuPiece::Patch>(std::make_move_iterator(begin),
                                       std::make_move_iterator(end)),
          names,
          ranges));
      }
    patches.clear();
    return pieces;
  }
} // namespace coulomb_adapt
