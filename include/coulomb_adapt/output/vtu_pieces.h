#ifndef coulomb_adapt_output_vtu_pieces_h
#define coulomb_adapt_output_vtu_pieces_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_out.h>

#include <string>
#include <tuple>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Some of a DataOut's patches, with its field names, as a
   * DataOutInterface of their own: what one `.vtu` piece holds.
   */
  class PatchPiece : public dealii::DataOutInterface<2, 2>
  {
  public:
    using Patch = dealii::DataOutBase::Patch<2, 2>;
    using NonscalarRanges = std::vector<
      std::tuple<unsigned int,
                 unsigned int,
                 std::string,
                 dealii::DataComponentInterpretation::
                   DataComponentInterpretation>>;

    PatchPiece(std::vector<Patch>              patches,
               const std::vector<std::string> &names,
               const NonscalarRanges          &ranges);

    const std::vector<Patch> &
    get_patches() const override;

    std::vector<std::string>
    get_dataset_names() const override;

    NonscalarRanges
    get_nonscalar_data_ranges() const override;

  private:
    std::vector<Patch>       patches;
    std::vector<std::string> names;
    NonscalarRanges          ranges;
  };



  /**
   * A DataOut whose patches, once built, can be handed out in pieces.
   * deal.II's VTU writer compresses a file in one stream on one thread;
   * pieces written concurrently use the cores the run has (on the
   * blocks run of benchmarks/adaptive_run zlib was two thirds of the
   * output, and the output's largest file is the last cycle's, which
   * nothing else can overlap).
   */
  class PieceableDataOut : public dealii::DataOut<2>
  {
  public:
    /** Move the patches into @p n_pieces pieces of consecutive patches
     * (as equal as can be); the DataOut keeps none. */
    std::vector<PatchPiece>
    take_pieces(const unsigned int n_pieces);
  };



  /**
   * How many pieces this rank's @p n_patches go into: one per thread
   * deal.II may use, but at least @p min_patches_per_piece patches each,
   * so that the small meshes of most runs (and of the tests) keep one
   * file per rank.
   */
  unsigned int
  n_vtu_pieces(const std::size_t  n_patches,
               const unsigned int n_threads,
               const std::size_t  min_patches_per_piece = 16384);
} // namespace coulomb_adapt

#endif
