#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <coulomb_adapt/output/contact_output.h>
#include <coulomb_adapt/output/file_writer.h>

#include <iomanip>

namespace coulomb_adapt
{
  ContactOutput::ContactOutput(const std::string &directory,
                               const MPI_Comm     comm)
    : directory(directory)
    , mpi_communicator(comm)
  {}



  void
  ContactOutput::write(const std::vector<ContactNodeState> &states,
                       const std::vector<double> &contact_error_density,
                       const unsigned int                   cycle,
                       const bool                           write_vtu)
  {
    // Every rank holds all slave nodes; rank 0 writes (write_file).
    const bool with_density = !contact_error_density.empty();
    const std::string base =
      directory + "/contact_" + Utilities::int_to_string(cycle, 3);

    write_file(mpi_communicator, base + ".csv", [&](std::ostream &csv) {
      csv << "x,y,normal_x,normal_y,weight,contact_pressure,"
             "tangential_traction,gap,slip,status,facing_master"
          << (with_density ? ",contact_error_density\n" : "\n");
      csv << std::setprecision(12);
      for (unsigned int j = 0; j < states.size(); ++j)
        {
          const ContactNodeState &s = states[j];
          csv << s.position[0] << ',' << s.position[1] << ',' << s.normal[0]
              << ',' << s.normal[1] << ',' << s.weight << ',' << s.pressure
              << ',' << s.tangential_traction << ',' << s.gap << ','
              << s.slip << ',' << to_string(s.status) << ','
              << (s.facing_master ? 1 : 0);
          if (with_density)
            csv << ',' << contact_error_density[j];
          csv << '\n';
        }
    });

    if (!write_vtu)
      return;

    write_file(mpi_communicator, base + ".vtu", [&](std::ostream &vtu) {
      // One 1D patch per pair of consecutive slave nodes (the nodes are
      // sorted along the interface); built where it is written, rank 0.
      std::vector<std::string> names = {
        "contact_pressure", "tangential_traction", "gap", "slip", "status"};
      if (with_density)
        names.emplace_back("contact_error_density");
      std::vector<DataOutBase::Patch<1, 2>> patches;
      for (unsigned int j = 0; j + 1 < states.size(); ++j)
        {
          DataOutBase::Patch<1, 2> patch;
          patch.n_subdivisions = 1;
          patch.reference_cell = ReferenceCells::Line;
          patch.data.reinit(names.size(), 2);
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
                patch.data(5, v) = contact_error_density[j + v];
            }
          patch.patch_index = j;
          patches.push_back(patch);
        }
      DataOutBase::write_vtu(
        patches,
        names,
        std::vector<
          std::tuple<unsigned int,
                     unsigned int,
                     std::string,
                     DataComponentInterpretation::DataComponentInterpretation>>(),
        DataOutBase::VtkFlags(),
        vtu);
    });
    pvd_records.emplace_back(cycle,
                             "contact_" + Utilities::int_to_string(cycle, 3) +
                               ".vtu");
    write_file(mpi_communicator,
               directory + "/contact.pvd",
               [&](std::ostream &pvd) {
                 DataOutBase::write_pvd_record(pvd, pvd_records);
               });
  }
} // namespace coulomb_adapt
