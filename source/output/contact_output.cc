#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/output/contact_output.h>
#include <coulomb_adapt/output/file_writer.h>

#include <iomanip>

namespace coulomb_adapt
{
  ContactOutput::ContactOutput(const std::string &directory,
                               const MPI_Comm     comm,
                               const OutputFormat format)
    : directory(directory)
    , mpi_communicator(comm)
    , format(format)
  {}



  namespace
  {
    using NoVectorFields = std::vector<
      std::tuple<unsigned int,
                 unsigned int,
                 std::string,
                 DataComponentInterpretation::DataComponentInterpretation>>;



    // The fields of the polyline, in the order of a patch's data rows.
    std::vector<std::string>
    field_names(const bool with_density)
    {
      std::vector<std::string> names = {
        "contact_pressure", "tangential_traction", "gap", "slip", "status"};
      if (with_density)
        names.emplace_back("contact_error_density");
      return names;
    }



    // One 1D patch per pair of consecutive slave nodes (the nodes are
    // sorted along the interface).
    std::vector<DataOutBase::Patch<1, 2>>
    polyline_patches(const std::vector<ContactNodeState> &states,
                     const std::vector<double>           &density,
                     const unsigned int                   n_fields,
                     const bool                           with_density)
    {
      std::vector<DataOutBase::Patch<1, 2>> patches;
      for (unsigned int j = 0; j + 1 < states.size(); ++j)
        {
          DataOutBase::Patch<1, 2> patch;
          patch.n_subdivisions = 1;
          patch.reference_cell = ReferenceCells::Line;
          patch.data.reinit(n_fields, 2);
          for (unsigned int v = 0; v < 2; ++v)
            {
              const ContactNodeState &s = states[j + v];
              patch.vertices[v]         = s.position;
              patch.data(0, v)          = s.pressure;
              patch.data(1, v)          = s.tangential_traction;
              patch.data(2, v)          = s.gap;
              patch.data(3, v)          = s.slip;
              // 0 open, 1 stick, 2 slip.
              patch.data(4, v) = static_cast<double>(s.status);
              if (with_density)
                patch.data(5, v) = density[j + v];
            }
          patch.patch_index = j;
          patches.push_back(patch);
        }
      return patches;
    }
  } // namespace



  void
  ContactOutput::write(const std::vector<ContactNodeState> &csv_states,
                       const std::vector<double>           &csv_density,
                       const unsigned int                   cycle,
                       const bool                           write_fields,
                       const std::vector<ContactNodeState> *field_states,
                       const std::vector<double>           *field_density)
  {
    const std::vector<ContactNodeState> &states =
      field_states != nullptr ? *field_states : csv_states;
    const std::vector<double> &contact_error_density =
      field_density != nullptr ? *field_density : csv_density;
    // Every rank holds all slave nodes; rank 0 writes (write_file).
    const bool        with_density = !csv_density.empty();
    const std::string stem = "contact_" + Utilities::int_to_string(cycle, 3);
    write_csv(csv_states, csv_density, directory + "/" + stem + ".csv");
    if (!write_fields)
      return;

    // The polyline is built where it is written, on rank 0.
    const std::vector<std::string> names = field_names(with_density);
    const std::vector<DataOutBase::Patch<1, 2>> patches =
      Utilities::MPI::this_mpi_process(mpi_communicator) == 0 ?
        polyline_patches(states,
                         contact_error_density,
                         names.size(),
                         with_density) :
        std::vector<DataOutBase::Patch<1, 2>>();
    if (format == OutputFormat::hdf5)
      {
        // An interface without slave nodes has no polyline to write.
        if (states.size() >= 2)
          write_hdf5_polyline(patches, names, stem, cycle);
      }
    else
      write_vtu_polyline(patches, names, stem, cycle);
  }



  void
  ContactOutput::write_csv(const std::vector<ContactNodeState> &states,
                           const std::vector<double>           &density,
                           const std::string                   &path) const
  {
    const bool with_density = !density.empty();
    write_file(mpi_communicator, path, [&](std::ostream &csv) {
      csv << "x,y,normal_x,normal_y,weight,contact_pressure,"
             "tangential_traction,gap,slip,status,facing_master"
          << (with_density ? ",contact_error_density\n" : "\n");
      csv << std::setprecision(12);
      for (unsigned int j = 0; j < states.size(); ++j)
        {
          const ContactNodeState &s = states[j];
          csv << s.position[0] << ',' << s.position[1] << ',' << s.normal[0]
              << ',' << s.normal[1] << ',' << s.weight << ',' << s.pressure
              << ',' << s.tangential_traction << ',' << s.gap << ',' << s.slip
              << ',' << to_string(s.status) << ',' << (s.facing_master ? 1 : 0);
          if (with_density)
            csv << ',' << density[j];
          csv << '\n';
        }
    });
  }



  // Rank 0 holds the polyline and writes it alone (MPI_COMM_SELF); its
  // error, if any, reaches every rank. Then the XDMF index of all cycles.
  void
  ContactOutput::write_hdf5_polyline(
    const std::vector<DataOutBase::Patch<1, 2>> &patches,
    const std::vector<std::string>              &names,
    const std::string                           &stem,
    const unsigned int                           cycle)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      try
        {
          DataOutBase::DataOutFilter filter(
            DataOutBase::DataOutFilterFlags(false, true));
          DataOutBase::write_filtered_data(patches,
                                           names,
                                           NoVectorFields(),
                                           filter);
          write_hdf5_file(MPI_COMM_SELF,
                          directory + "/" + stem + ".h5",
                          [&](const std::string &temporary) {
                            DataOutBase::write_hdf5_parallel(patches,
                                                             filter,
                                                             temporary,
                                                             MPI_COMM_SELF);
                          });
          XDMFEntry entry(stem + ".h5",
                          stem + ".h5",
                          cycle,
                          filter.n_nodes(),
                          filter.n_cells(),
                          1,
                          2);
          for (unsigned int i = 0; i < filter.n_data_sets(); ++i)
            entry.add_attribute(filter.get_data_set_name(i),
                                filter.get_data_set_dim(i));
          xdmf_entries.push_back(entry);
        }
      catch (const std::exception &e)
        {
          error = user_message(e);
        }
    error = Utilities::MPI::broadcast(mpi_communicator, error, 0);
    AssertThrow(error.empty(), ExcMessage(error));
    write_xdmf_file(mpi_communicator,
                    directory + "/contact.xdmf",
                    xdmf_entries,
                    ReferenceCells::Line);
  }



  // The polyline's VTU file (rank 0); write_index() lists it. No date in
  // the header, as for the bodies' pieces: two identical runs write
  // identical files.
  void
  ContactOutput::write_vtu_polyline(
    const std::vector<DataOutBase::Patch<1, 2>> &patches,
    const std::vector<std::string>              &names,
    const std::string                           &stem,
    const unsigned int                           cycle)
  {
    write_file(mpi_communicator,
               directory + "/" + stem + ".vtu",
               [&](std::ostream &vtu) {
                 DataOutBase::VtkFlags vtk_flags;
                 vtk_flags.compression_level =
                   DataOutBase::VtkFlags::best_speed;
                 vtk_flags.print_date_and_time = false;
                 DataOutBase::write_vtu(
                   patches, names, NoVectorFields(), vtk_flags, vtu);
               });
    pvd_records.emplace_back(cycle, stem + ".vtu");
  }



  void
  ContactOutput::write_index(const unsigned int last_cycle) const
  {
    if (format != OutputFormat::vtu || pvd_records.empty())
      return;
    std::vector<std::pair<double, std::string>> listed;
    for (const auto &record : pvd_records)
      if (record.first <= last_cycle)
        listed.push_back(record);
    write_file(mpi_communicator,
               directory + "/contact.pvd",
               [&](std::ostream &pvd) {
                 DataOutBase::write_pvd_record(pvd, listed);
               });
  }
} // namespace coulomb_adapt
