#ifndef coulomb_adapt_output_vtu_pieces_h
#define coulomb_adapt_output_vtu_pieces_h

#include <deal.II/base/data_out_base.h>

#include <deal.II/numerics/data_out.h>

#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace coulomb_adapt
{
  /**
   * Some of a DataOut's patches (one per cell) with its field names: what
   * deal.II's VTU writer needs to write them as one piece of a .pvtu
   * record. The pieces of one rank are written by concurrent tasks
   * (file_writer.h): deal.II's writer encodes and compresses a file on
   * one thread, which made the writing of a large body the longest part
   * of the output (benchmarks/adaptive_run).
   */
  class VtuPiece : public dealii::DataOutInterface<2, 2>
  {
  public:
    using Patch           = dealii::DataOutBase::Patch<2, 2>;
    using NonscalarRanges = std::vector<std::tuple<
      unsigned int,
      unsigned int,
      std::string,
      dealii::DataComponentInterpretation::DataComponentInterpretation>>;

    VtuPiece(std::vector<Patch>       patches,
             std::vector<std::string> names,
             NonscalarRanges          nonscalar_ranges);

  protected:
    const std::vector<Patch> &
    get_patches() const override;
    std::vector<std::string>
    get_dataset_names() const override;
    NonscalarRanges
    get_nonscalar_data_ranges() const override;

  private:
    const std::vector<Patch>       patches;
    const std::vector<std::string> names;
    const NonscalarRanges          nonscalar_ranges;
  };



  /**
   * A DataOut<2> whose patches, once built, are handed over as VtuPieces
   * of at most a given number of cells.
   */
  class DataOutInPieces : public dealii::DataOut<2>
  {
  public:
    /**
     * The patches in order, in ceil(n / @p max_cells) pieces of sizes
     * that differ by at most one (one piece, perhaps empty, when
     * @p max_cells is 0 or at least n). The count depends on the cells
     * alone, not on the threads, so that the files a run writes do too.
     * The patches are moved: this object has none left afterwards.
     */
    std::vector<std::unique_ptr<VtuPiece>>
    take_pieces(const unsigned int max_cells);
  };
} // namespace coulomb_adapt

#endif
