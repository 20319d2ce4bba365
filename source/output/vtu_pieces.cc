#include <coulomb_adapt/output/vtu_pieces.h>

#include <algorithm>
#include <iterator>

namespace coulomb_adapt
{
  using namespace dealii;

  PatchPiece::PatchPiece(std::vector<Patch>              patches,
                         const std::vector<std::string> &names,
                         const NonscalarRanges          &ranges)
    : patches(std::move(patches))
    , names(names)
    , ranges(ranges)
  {}



  const std::vector<PatchPiece::Patch> &
  PatchPiece::get_patches() const
  {
    return patches;
  }



  std::vector<std::string>
  PatchPiece::get_dataset_names() const
  {
    return names;
  }



  PatchPiece::NonscalarRanges
  PatchPiece::get_nonscalar_data_ranges() const
  {
    return ranges;
  }



  std::vector<PatchPiece>
  PieceableDataOut::take_pieces(const unsigned int n_pieces)
  {
    Assert(n_pieces > 0, ExcMessage("at least one piece"));
    const std::vector<std::string>     dataset_names = get_dataset_names();
    const PatchPiece::NonscalarRanges  ranges = get_nonscalar_data_ranges();
    std::vector<PatchPiece>            pieces;
    const std::size_t                  n_patches = patches.size();
    for (unsigned int k = 0; k < n_pieces; ++k)
      {
        const auto begin = patches.begin() + k * n_patches / n_pieces;
        const auto end   = patches.begin() + (k + 1) * n_patches / n_pieces;
        pieces.emplace_back(
          std::vector<PatchPiece::Patch>(std::make_move_iterator(begin),
                                         std::make_move_iterator(end)),
          dataset_names,
          ranges);
      }
    patches.clear();
    return pieces;
  }



  unsigned int
  n_vtu_pieces(const std::size_t  n_patches,
               const unsigned int n_threads,
               const std::size_t  min_patches_per_piece)
  {
    const std::size_t by_size =
      std::max<std::size_t>(1, n_patches / min_patches_per_piece);
    return static_cast<unsigned int>(
      std::min<std::size_t>(std::max(1u, n_threads), by_size));
  }
} // namespace coulomb_adapt
