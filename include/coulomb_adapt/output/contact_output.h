#ifndef coulomb_adapt_output_contact_output_h
#define coulomb_adapt_output_contact_output_h

#include <deal.II/base/data_out_base.h>

#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/core/options.h>

#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The contact interface's nodal results per cycle:
   * `contact_<cycle>.csv` (one row per slave node, sorted along the
   * interface) and a polyline through the slave nodes with the same fields
   * as point data, so that ParaView shows it beside the bodies: with
   * @p format "vtu" `contact_<cycle>.vtu` indexed by `contact.pvd`, with
   * "hdf5" `contact_<cycle>.h5` indexed by `contact.xdmf`. Written by
   * rank 0 (every rank holds the whole interface).
   */
  class ContactOutput
  {
  public:
    ContactOutput(const std::string &directory,
                  const MPI_Comm     comm,
                  const OutputFormat format);

    /** Write the CSV, and with @p write_fields the polyline and its index.
     * @p contact_error_density (one value per slave node, may be empty) is
     * the density of the indicator's contact term. The polyline gets
     * @p field_states and @p field_density where given (a scaled
     * problem, VTU or HDF5: the CSV's doubles hold the physical values,
     * the 32-bit floats of deal.II's patches only the scaled ones). */
    void
    write(const std::vector<ContactNodeState> &states,
          const std::vector<double>           &contact_error_density,
          const unsigned int                   cycle,
          const bool                           write_fields,
          const std::vector<ContactNodeState> *field_states  = nullptr,
          const std::vector<double>           *field_density = nullptr);

    /** With Format = vtu: contact.pvd, listing the polylines of the
     * cycles up to @p last_cycle, those whose bodies' fields are complete
     * (Output/Write in background): no index lists a cycle whose body
     * files are missing. Collective. */
    void
    write_index(const unsigned int last_cycle) const;

  private:
    /** One row per slave node into @p path (rank 0). */
    void
    write_csv(const std::vector<ContactNodeState> &states,
              const std::vector<double>           &density,
              const std::string                   &path) const;
    /** The polyline @p patches as `STEM.h5` and the index contact.xdmf. */
    void
    write_hdf5_polyline(const std::vector<DataOutBase::Patch<1, 2>> &patches,
                        const std::vector<std::string>              &names,
                        const std::string                           &stem,
                        const unsigned int                           cycle);
    /** The polyline @p patches as `STEM.vtu` (indexed by write_index()). */
    void
    write_vtu_polyline(const std::vector<DataOutBase::Patch<1, 2>> &patches,
                       const std::vector<std::string>              &names,
                       const std::string                           &stem,
                       const unsigned int                           cycle);

    const std::string                           directory;
    const MPI_Comm                              mpi_communicator;
    const OutputFormat                          format;
    std::vector<std::pair<double, std::string>> pvd_records;
    std::vector<XDMFEntry>                      xdmf_entries;
  };
} // namespace coulomb_adapt

#endif
