#ifndef coulomb_adapt_output_body_output_h
#define coulomb_adapt_output_body_output_h

#include <deal.II/base/data_out_base.h>

#include <deal.II/lac/vector.h>

#include <deal.II/numerics/data_out.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/core/options.h>
#include <coulomb_adapt/indicator/recovered_stress.h>
#include <coulomb_adapt/output/file_writer.h>
#include <coulomb_adapt/output/vtu_pieces.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /** The indicator's fields of a body, when it was computed. */
  struct BodyErrorFields
  {
    const Vector<float>   *indicator = nullptr;
    const Vector<float>   *density   = nullptr;
    const RecoveredStress *recovered = nullptr;
  };

  /**
   * The subdivisions of each cell of @p tria in the output of @p format
   * for elements of degree @p degree: p, but 1 for triangles in HDF5
   * (deal.II 9.4's HDF5 writer cannot write the cells of degree p that
   * P_p triangles give; the fields are written at the triangles'
   * vertices).
   */
  unsigned int
  patch_subdivisions(const Triangulation<2> &tria,
                     const unsigned int      degree,
                     const OutputFormat      format);



  /**
   * Writes one body's fields per cycle, and an index of all cycles written
   * so far, so that ParaView shows the cycles as a time series (the cycle
   * number is the time). @p format "vtu": `<base>_<cycle>.pvtu` (+ the
   * `.vtu` pieces, at least one per rank, of at most
   * @p cells_per_vtu_piece cells each, 0: one per rank) indexed by
   * `<base>.pvd`; "hdf5": `<base>_<cycle>.h5` (all ranks write into one
   * file) indexed by `<base>.xdmf`.
   */
  class BodyOutput
  {
  public:
    BodyOutput(const std::string &directory,
               const std::string &base_name,
               const OutputFormat format,
               const unsigned int cells_per_vtu_piece);

    /** The fields of the body's solution as solved: for a scaled
     * problem (core/units.h) those of the scaled problem, in both formats,
     * since deal.II's patches hold 32-bit floats (1e-38 ... 3e38), which
     * would not hold the physical ones (the log and summary.json give
     * the factors). */
    void
    write(const ElasticBody     &body,
          const unsigned int     cycle,
          const BodyErrorFields &error_fields  = BodyErrorFields(),
          const bool             in_background = false);

    /** With Format = vtu and @p in_background, write() returns once the
     * fields are in the patches, and the pieces are encoded, compressed
     * and written on a thread of their own (file_writer.h,
     * VtuRecordWrite) until this call or the object's end (which removes
     * them). Collective: completes that cycle (its .pvtu) and returns its
     * index record (cycle, .pvtu), which add_to_index() adds once the
     * other body's is complete too; none if nothing was pending. */
    std::optional<std::pair<unsigned int, std::string>>
    finish_background_write(const MPI_Comm comm);

    void
    add_to_index(const std::pair<unsigned int, std::string> &record);

    /** The index of every cycle written (`<base>.pvd` or `<base>.xdmf`).
     * Apart from write(), so that a run indexes a cycle only once all of
     * its files are written: with body 2's file failing, body 1's index
     * listed a cycle that the others did not. A cycle written in the
     * background is indexed once complete_background_write() has
     * completed it. */
    void
    write_index(const MPI_Comm comm) const;

  private:
    /** The cycle's `<base>_<cycle>.h5`; @p reference_cell_of_cells is
     * the element's (known to every rank, also one without cells). */
    void
    write_hdf5_cycle(const DataOut<2>    &data_out,
                     const MPI_Comm       comm,
                     const ReferenceCell &reference_cell_of_cells,
                     const unsigned int   cycle);
    /** The cycle's `.pvtu` (+ its `.vtu` pieces). */
    void
    write_vtu_cycle(DataOutInPieces   &data_out,
                    const MPI_Comm     comm,
                    const unsigned int cycle,
                    const bool         in_background);

    const std::string                           directory;
    const std::string                           base_name;
    const OutputFormat                          format;
    const unsigned int                          cells_per_vtu_piece;
    std::vector<std::pair<double, std::string>> pvd_records;
    /** The cycle being written in the background, if any. */
    std::unique_ptr<VtuRecordWrite> background_write;
    unsigned int                    background_cycle = 0;
    std::vector<XDMFEntry>          xdmf_entries;
    /** The reference cell of the meshes written (for the XDMF index). */
    ReferenceCell reference_cell;
  };
} // namespace coulomb_adapt

#endif
