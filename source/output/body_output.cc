#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <deal.II/numerics/data_out.h>

#include <coulomb_adapt/output/body_output.h>
#include <coulomb_adapt/output/displacement_stress_postprocessor.h>
#include <coulomb_adapt/output/file_writer.h>

#include <array>
#include <optional>
#include <string>

namespace coulomb_adapt
{
  BodyOutput::BodyOutput(const std::string &directory,
                         const std::string &base_name,
                         const OutputFormat format,
                         const unsigned int cells_per_vtu_piece)
    : directory(directory)
    , base_name(base_name)
    , format(format)
    , cells_per_vtu_piece(cells_per_vtu_piece)
  {}



  namespace
  {
    // The partition, on more than one rank (on one it is 0 everywhere).
    // No material id: each body has one (its file holds one body), a
    // constant field that showed nothing and cost about a twelfth of the
    // writing (benchmarks/adaptive_run).
    std::optional<Vector<float>>
    subdomain_field(const Triangulation<2> &tria)
    {
      if (Utilities::MPI::n_mpi_processes(tria.get_communicator()) == 1)
        return std::nullopt;
      Vector<float> subdomain(tria.n_active_cells());
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          subdomain(cell->active_cell_index()) = cell->subdomain_id();
      return subdomain;
    }



    // The indicator's fields, where computed.
    void
    add_error_fields(DataOut<2> &data_out, const BodyErrorFields &error_fields)
    {
      if (error_fields.indicator)
        data_out.add_data_vector(*error_fields.indicator, "error_indicator");
      if (error_fields.density)
        data_out.add_data_vector(*error_fields.density, "error_density");
      if (error_fields.recovered)
        {
          const std::array<std::string, 3> names = {
            {"smoothed_stress_xx", "smoothed_stress_yy", "smoothed_stress_xy"}};
          for (unsigned int c = 0; c < 3; ++c)
            data_out.add_data_vector(error_fields.recovered->dof_handler(),
                                     error_fields.recovered->component(c),
                                     names[c]);
        }
    }
  } // namespace



  unsigned int
  patch_subdivisions(const Triangulation<2> &tria,
                     const unsigned int      degree,
                     const OutputFormat      format)
  {
    // deal.II 9.4 writes P_p triangles as cells of degree p, which its
    // HDF5 writer (DataOutFilter) does not know: with P2 it overran a
    // buffer and the run died (SIGSEGV, no message). HDF5 gets the
    // triangles with their vertices' values instead. Quadrilaterals of
    // degree p are written as p x p linear cells by both writers.
    if (format == OutputFormat::hdf5 && tria.all_reference_cells_are_simplex())
      return 1;
    return degree;
  }



  void
  BodyOutput::write(const ElasticBody     &body,
                    const unsigned int     cycle,
                    const BodyErrorFields &error_fields,
                    const bool             in_background)
  {
    // One cycle at a time in the background: the caller completes the
    // earlier one first (TwoBodyProblem::complete_background_writes).
    Assert(!background_write, ExcInternalError());
    const Triangulation<2> &tria = body.triangulation();
    DataOutInPieces         data_out;
    data_out.attach_dof_handler(body.dof_handler());
    const DisplacementStressPostprocessor fields(body.material());
    data_out.add_data_vector(body.solution(), fields);
    const std::optional<Vector<float>> subdomain = subdomain_field(tria);
    add_error_fields(data_out, error_fields);
    if (subdomain)
      data_out.add_data_vector(*subdomain, "subdomain");

    data_out.build_patches(
      body.mapping(),
      patch_subdivisions(tria, body.dof_handler().get_fe().degree, format),
      DataOut<2>::curved_inner_cells);
    if (format == OutputFormat::hdf5)
      write_hdf5_cycle(data_out,
                       tria.get_communicator(),
                       body.dof_handler().get_fe().reference_cell(),
                       cycle);
    else
      write_vtu_cycle(data_out, tria.get_communicator(), cycle, in_background);
  }



  std::optional<std::pair<unsigned int, std::string>>
  BodyOutput::finish_background_write(const MPI_Comm comm)
  {
    if (!background_write)
      return std::nullopt;
    // Gone whether it succeeds or throws: its temporary files are
    // removed on failure, and the error ends the run.
    const std::unique_ptr<VtuRecordWrite> write = std::move(background_write);
    return std::make_pair(background_cycle, write->finish(comm));
  }



  void
  BodyOutput::add_to_index(const std::pair<unsigned int, std::string> &record)
  {
    pvd_records.emplace_back(record.first, record.second);
  }



  void
  BodyOutput::write_hdf5_cycle(const DataOut<2>    &data_out,
                               const MPI_Comm       comm,
                               const ReferenceCell &reference_cell_of_cells,
                               const unsigned int   cycle)
  {
    const std::string h5 =
      base_name + "_" + Utilities::int_to_string(cycle, 3) + ".h5";
    xdmf_entries.push_back(write_hdf5(comm, data_out, directory, h5, cycle));
    // From the element, which every rank has: a rank may own no cells.
    reference_cell = reference_cell_of_cells;
  }



  void
  BodyOutput::write_index(const MPI_Comm comm) const
  {
    if (format == OutputFormat::hdf5)
      write_xdmf_file(comm,
                      directory + "/" + base_name + ".xdmf",
                      xdmf_entries,
                      reference_cell);
    else
      write_file(comm,
                 directory + "/" + base_name + ".pvd",
                 [&](std::ostream &pvd) {
                   DataOutBase::write_pvd_record(pvd, pvd_records);
                 });
  }



  // zlib's fastest level instead of deal.II's default, the best
  // compression: on these fields the files are hardly larger, and writing
  // them no longer dominates an adaptive run (benchmarks/adaptive_run).
  // No date in the .vtu headers: two identical runs write identical
  // pieces (deal.II dates the .pvtu and .pvd records whatever the flags).
  void
  BodyOutput::write_vtu_cycle(DataOutInPieces   &data_out,
                              const MPI_Comm     comm,
                              const unsigned int cycle,
                              const bool         in_background)
  {
    DataOutBase::VtkFlags vtk_flags;
    vtk_flags.compression_level   = DataOutBase::VtkFlags::best_speed;
    vtk_flags.print_date_and_time = false;
    background_write              = std::make_unique<VtuRecordWrite>(comm,
                                                        data_out.take_pieces(
                                                          cells_per_vtu_piece),
                                                        vtk_flags,
                                                        directory,
                                                        base_name,
                                                        cycle,
                                                        in_background);
    background_cycle              = cycle;
    if (!in_background)
      add_to_index(*finish_background_write(comm));
  }
} // namespace coulomb_adapt
