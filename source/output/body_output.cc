#include <deal.II/base/data_out_base.h>

#include <deal.II/numerics/data_out.h>

#include <coulomb_adapt/output/body_output.h>
#include <coulomb_adapt/output/file_writer.h>
#include <coulomb_adapt/output/stress_postprocessor.h>

#include <array>
#include <string>

namespace coulomb_adapt
{
  BodyOutput::BodyOutput(const std::string &directory,
                         const std::string &base_name,
                         const OutputFormat format)
    : directory(directory)
    , base_name(base_name)
    , format(format)
  {}



  void
  BodyOutput::write(const ElasticBody     &body,
                    const unsigned int     cycle,
                    const BodyErrorFields &error_fields)
  {
    const Triangulation<2> &tria = body.triangulation();
    const MPI_Comm          comm = tria.get_communicator();

    DataOut<2> data_out;
    data_out.attach_dof_handler(body.dof_handler());
    data_out.add_data_vector(
      body.solution(),
      std::vector<std::string>(2, "displacement"),
      DataOut<2>::type_dof_data,
      std::vector<DataComponentInterpretation::DataComponentInterpretation>(
        2, DataComponentInterpretation::component_is_part_of_vector));
    const StressPostprocessor stresses(body.material());
    data_out.add_data_vector(body.solution(), stresses);

    Vector<float> material_id(tria.n_active_cells());
    Vector<float> subdomain(tria.n_active_cells());
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          material_id(cell->active_cell_index()) = cell->material_id();
          subdomain(cell->active_cell_index())   = cell->subdomain_id();
        }
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
    data_out.add_data_vector(material_id, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");

    data_out.build_patches(body.mapping(),
                           body.dof_handler().get_fe().degree,
                           DataOut<2>::curved_inner_cells);

    if (format == OutputFormat::hdf5)
      {
        const std::string h5 =
          base_name + "_" + Utilities::int_to_string(cycle, 3) + ".h5";
        xdmf_entries.push_back(
          write_hdf5(comm, data_out, directory, h5, cycle));
        write_xdmf_file(comm,
                        directory + "/" + base_name + ".xdmf",
                        xdmf_entries,
                        tria.get_reference_cells()[0]);
        return;
      }

    // zlib's fastest level instead of deal.II's default, the best
    // compression: on these fields the files are hardly larger, and
    // writing them no longer dominates an adaptive run
    // (benchmarks/adaptive_run).
    DataOutBase::VtkFlags vtk_flags;
    vtk_flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(vtk_flags);
    const std::string pvtu =
      write_vtu_with_pvtu_record(comm, data_out, directory, base_name, cycle);

    pvd_records.emplace_back(cycle, pvtu);
    write_file(comm,
               directory + "/" + base_name + ".pvd",
               [&](std::ostream &pvd) {
                 DataOutBase::write_pvd_record(pvd, pvd_records);
               });
  }
} // namespace coulomb_adapt
