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
   * A DataOut's patches (one per cell) cut into pieces, with the field
   * names: what deal.II's VTU writer (DataOutBase::write_vtu and
   * write_pvtu_record) needs to write each piece as one file of a .pvtu
   * record. The pieces of one rank are written by concurrent tasks
   * (file_writer.h): deal.II's writer encodes and compresses a file on
   * one thread, which made the writing of a large body the longest part
   * of the output (benchmarks/adaptive_run).
   */
  struct VtuPieces
  {
    using Patch           = dealii::DataOutBase::Patch<2, 2>;
    using NonscalarRanges = std::vector<std::tuple<
      unsigned int,
      unsigned int,
      std::string,
      dealii::DataComponentInterpretation::DataComponentInterpretation>>;

    /** The patches of each piece, in the cells' order. */
    std::vector<std::vector<Patch>> patches;
    std::vector<std::string>        names;
    NonscalarRanges                 nonscalar_ranges;
  };



  /**
   * A DataOut<2> whose patches, once built, are handed over in pieces of
   * at most a given number of cells (DataOut keeps them protected).
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
    VtuPieces
    take_pieces(const unsigned int max_cells);
  };
} // namespace coulomb_adapt

#endif
