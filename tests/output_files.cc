// What the program writes, by Output/Format and Output/Write cycles, on
// blocks with P1 triangles refined uniformly (two cycles, the same meshes
// on any number of ranks):
//  - hdf5: one .xdmf per body and one for the contact line, each indexing
//    both cycles; every .h5 they name exists and, opened back with the HDF5
//    library, holds as many cells as the body (the contact line: one
//    segment per pair of neighbouring slave nodes of the CSV) and three
//    nodes per triangle (duplicate vertices are kept for the cell data),
//    the sizes the XDMF entry states, and a displacement whose largest
//    component is the solution vector's max norm;
//  - Write cycles = last: the fields of the last cycle only (one record in
//    each .pvd), the contact CSV and summary.json of every cycle;
//  - Write cycles = none: no field file at all, CSV and summary.json still;
//  - no temporary file (NAME.tmp) is left behind;
//  - hdf5 with P2 triangles (before: SIGSEGV in deal.II's HDF5 writer, no
//    message): the triangles at their vertices, three nodes each, and the
//    largest displacement written is within that of the solution's nodes;
//  - hdf5 of a scaled problem (pressure 1e300, load scale 2^997): the
//    fields of the scaled problem, as in VTU (before: the physical values,
//    which 32-bit floats turned into inf), summary.json listing
//    'HDF5 fields' in reported_scaled;
//  - pressures 1e40 and 1e-40, whose stresses or displacements 32-bit
//    floats cannot hold as they are: solved and written scaled, the
//    written von Mises stress and displacement those of pressure 1 times
//    pressure / scale to the floats' rounding (before: inf and subnormal
//    values, the problem solved as given).
// MPI-IO is chosen as main() chooses it (app/parallel_file_io.h): with
// OMPIO, a locked semaphore of another run's body-1_000.h5.tmp
// (bad_input.stale_io_semaphore plants one) would stop this test.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/app/parallel_file_io.h>
#include <coulomb_adapt/app/two_body_problem.h>

#include "program_run.h"
#include "test_utilities.h"

#include <hdf5.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>

using namespace coulomb_adapt;

namespace
{
  using testing::ProgramRun;
  using testing::read_text;
  using testing::Settings;

  Settings
  blocks(const std::string &format,
         const std::string &write_cycles,
         const std::string &directory)
  {
    return {{"Scene/Name", "blocks"},
            {"Scene/Blocks/Upper body subdivisions", "2, 2"},
            {"Scene/Blocks/Lower body subdivisions", "4, 4"},
            {"Contact/Friction coefficient", "0.3"},
            {"Mesh/Cell type", "triangle"},
            {"Adaptation/Strategy", "uniform"},
            {"Adaptation/Target error", "0"},
            {"Adaptation/Number of cycles", "2"},
            {"Output/Format", format},
            {"Output/Write cycles", write_cycles},
            {"Output/Output directory", directory}};
  }

  // The directory's file names, sorted.
  std::vector<std::string>
  files_in(const std::string &directory)
  {
    std::vector<std::string> names;
    for (const auto &entry : std::filesystem::directory_iterator(directory))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }


  unsigned int
  count(const std::string &text, const std::string &what)
  {
    unsigned int n = 0;
    for (std::size_t p = text.find(what); p != std::string::npos;
         p             = text.find(what, p + 1))
      ++n;
    return n;
  }

  // Rows and columns of a two-dimensional data set of an HDF5 file.
  std::array<hsize_t, 2>
  dimensions(const hid_t file, const std::string &data_set)
  {
    const hid_t set = H5Dopen2(file, data_set.c_str(), H5P_DEFAULT);
    AssertThrow(set >= 0, ExcMessage("no data set " + data_set));
    const hid_t            space = H5Dget_space(set);
    std::array<hsize_t, 2> dims  = {{0, 1}};
    AssertThrow(H5Sget_simple_extent_ndims(space) <= 2, ExcInternalError());
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(set);
    return dims;
  }

  double
  max_abs(const hid_t file, const std::string &data_set)
  {
    const auto          dims = dimensions(file, data_set);
    std::vector<double> values(dims[0] * dims[1]);
    const hid_t         set = H5Dopen2(file, data_set.c_str(), H5P_DEFAULT);
    H5Dread(
      set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(set);
    double m = 0;
    for (const double v : values)
      m = std::max(m, std::abs(v));
    return m;
  }

  // The .h5 files an XDMF file names, in order, and the "rows cols" of its
  // topology and geometry data items.
  struct XdmfEntryText
  {
    std::string h5;
    std::string cells, nodes;
  };

  std::vector<XdmfEntryText>
  xdmf_entries(const std::string &path)
  {
    const std::string text = read_text(path);
    const std::regex  grid(
      "<Geometry[^>]*>\\s*<DataItem Dimensions=\"([0-9 ]+)\"[^>]*>\\s*"
       "([^:\\s]+):/nodes[\\s\\S]*?<Topology[^>]*>\\s*<DataItem "
       "Dimensions=\"([0-9 ]+)\"");
    std::vector<XdmfEntryText> entries;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), grid);
         it != std::sregex_iterator();
         ++it)
      entries.push_back({(*it)[2], (*it)[3], (*it)[1]});
    return entries;
  }

  void
  check_no_temporary_files(const std::string  &directory,
                           ConditionalOStream &out)
  {
    unsigned int n = 0;
    for (const auto &name : files_in(directory))
      n += name.size() > 4 && name.substr(name.size() - 4) == ".tmp";
    out << "  temporary files left: " << n << std::endl;
    AssertThrow(n == 0, ExcMessage("a .tmp file was left behind"));
  }

  void
  check_hdf5(ConditionalOStream &out)
  {
    out << "Format = hdf5, Write cycles = all" << std::endl;
    const ProgramRun  run(blocks("hdf5", "all", "output-hdf5"));
    const std::string directory = run.parameters.output.directory;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        const std::vector<std::string> bases = {"body-1", "body-2", "contact"};
        for (unsigned int k = 0; k < 3; ++k)
          {
            const auto entries =
              xdmf_entries(directory + "/" + bases[k] + ".xdmf");
            out << "  " << bases[k] << ".xdmf: " << entries.size() << " cycles"
                << std::endl;
            AssertThrow(entries.size() == 2,
                        ExcMessage("the XDMF file does not index 2 cycles"));
            for (unsigned int c = 0; c < entries.size(); ++c)
              {
                const std::string h5 = directory + "/" + entries[c].h5;
                AssertThrow(std::filesystem::exists(h5),
                            ExcMessage("missing " + h5));
                const hid_t file =
                  H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
                AssertThrow(file >= 0, ExcMessage("cannot open " + h5));
                const auto cells = dimensions(file, "/cells");
                const auto nodes = dimensions(file, "/nodes");
                // What the mesh says: a body's triangles, or one segment
                // per pair of neighbouring slave nodes (the CSV's rows).
                std::size_t expected_cells = 0, nodes_per_cell = 3;
                if (k < 2)
                  expected_cells =
                    run.summary["cycles"][c]["bodies"][k]["n_cells"]
                      .get<std::size_t>();
                else
                  {
                    const std::string csv =
                      read_text(directory + "/contact_" +
                                Utilities::int_to_string(c, 3) + ".csv");
                    expected_cells = count(csv, "\n") - 2;
                    nodes_per_cell = 2;
                  }
                out << "    " << entries[c].h5 << ": cells " << cells[0]
                    << " x " << cells[1] << ", nodes " << nodes[0] << " x "
                    << nodes[1] << " (XDMF: " << entries[c].cells << ", "
                    << entries[c].nodes << "; expected " << expected_cells
                    << " cells)" << std::endl;
                AssertThrow(cells[0] == expected_cells &&
                              cells[1] == nodes_per_cell &&
                              nodes[0] == nodes_per_cell * expected_cells &&
                              nodes[1] == 2,
                            ExcMessage("wrong sizes in " + h5));
                AssertThrow(entries[c].cells == std::to_string(cells[0]) + " " +
                                                  std::to_string(cells[1]) &&
                              entries[c].nodes ==
                                std::to_string(nodes[0]) + " 2",
                            ExcMessage("the XDMF sizes differ from " + h5));
                H5Fclose(file);
              }
          }
      }
    // The last cycle's displacement, against the solution vectors.
    for (unsigned int b = 0; b < 2; ++b)
      {
        const double expected = run.problem->body(b).solution().linfty_norm();
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          {
            const std::string h5 =
              directory + "/body-" + std::to_string(b + 1) + "_001.h5";
            const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
            const double written = max_abs(file, "/displacement");
            H5Fclose(file);
            out << "  body " << b + 1 << ", cycle 1: max |u| written "
                << written << " mm, of the solution " << expected << " mm"
                << std::endl;
            // DataOut keeps the fields in single precision.
            AssertThrow(std::abs(written - expected) <= 1.2e-7 * expected,
                        ExcMessage("the written displacement differs"));
          }
      }
    check_no_temporary_files(directory, out);
  }

  // The largest |value| of @p field in body @p b's .h5 of @p cycle (rank
  // 0; 0 elsewhere).
  double
  written_maximum(const std::string &directory,
                  const unsigned int b,
                  const unsigned int cycle,
                  const std::string &field = "displacement")
  {
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return 0;
    const std::string h5 = directory + "/body-" + std::to_string(b + 1) + "_" +
                           Utilities::int_to_string(cycle, 3) + ".h5";
    const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    AssertThrow(file >= 0, ExcMessage("cannot open " + h5));
    const double written = max_abs(file, "/" + field);
    H5Fclose(file);
    return written;
  }

  // One cycle of blocks in HDF5 into @p directory, with @p setting.
  Settings
  one_hdf5_cycle(const std::string                         &directory,
                 const std::pair<std::string, std::string> &setting)
  {
    Settings settings = blocks("hdf5", "all", directory);
    settings.push_back(setting);
    settings.push_back({"Adaptation/Number of cycles", "1"});
    return settings;
  }

  void
  check_hdf5_quadratic_triangles(ConditionalOStream &out)
  {
    out << "Format = hdf5, P2 triangles" << std::endl;
    const ProgramRun run(
      one_hdf5_cycle("output-hdf5-p2",
                     {"Finite elements/Polynomial degree", "2"}));
    const std::string directory = run.parameters.output.directory;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const double nodes_max = run.problem->body(b).solution().linfty_norm();
        const double written   = written_maximum(directory, b, 0);
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
          continue;
        const std::string h5 =
          directory + "/body-" + std::to_string(b + 1) + "_000.h5";
        const hid_t file  = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        const auto  cells = dimensions(file, "/cells");
        const auto  nodes = dimensions(file, "/nodes");
        H5Fclose(file);
        const std::size_t n_cells =
          run.summary["cycles"][0]["bodies"][b]["n_cells"].get<std::size_t>();
        out << "  body " << b + 1 << ": cells " << cells[0] << " x " << cells[1]
            << ", nodes " << nodes[0] << " (" << n_cells
            << " triangles); max |u| written " << written
            << " mm, of the solution's nodes " << nodes_max << " mm"
            << std::endl;
        AssertThrow(cells[0] == n_cells && cells[1] == 3 &&
                      nodes[0] == 3 * n_cells,
                    ExcMessage("not the triangles at their vertices"));
        AssertThrow(written > 0 && written <= nodes_max * (1 + 1.2e-7),
                    ExcMessage("displacement not that of the solution"));
      }
    check_no_temporary_files(directory, out);
  }

  void
  check_hdf5_scaled_problem(ConditionalOStream &out)
  {
    out << "Format = hdf5, pressure 1e300" << std::endl;
    const ProgramRun run(
      one_hdf5_cycle("output-hdf5-scaled", {"Scene/Blocks/Pressure", "1e300"}));
    const double load_scale = run.summary.value("load_scale", 0.);
    bool         listed     = false;
    for (const auto &entry :
         run.summary.value("reported_scaled", nlohmann::json::array()))
      listed = listed || entry.dump().find("HDF5 fields") != std::string::npos;
    out << "  load scale 2^" << std::log2(load_scale)
        << ", reported_scaled lists 'HDF5 fields': " << (listed ? "yes" : "no")
        << std::endl;
    AssertThrow(load_scale > 1e299 && listed,
                ExcMessage("not scaled, or the HDF5 fields not listed"));
    for (unsigned int b = 0; b < 2; ++b)
      {
        const double scaled = run.problem->body(b).solution().linfty_norm();
        const double written =
          written_maximum(run.parameters.output.directory, b, 0);
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
          continue;
        out << "  body " << b + 1 << ": max |u| written " << written
            << " mm, of the scaled problem's solution " << scaled << " mm"
            << std::endl;
        AssertThrow(std::isfinite(written) &&
                      std::abs(written - scaled) <= 1.2e-7 * scaled,
                    ExcMessage("not the scaled problem's displacement"));
      }
  }

  // Pressures whose fields 32-bit floats cannot hold as they are (1e40:
  // stresses beyond 3.4e38; 1e-40: displacements and stresses below
  // 1.2e-38, subnormal or 0), solved and written scaled: by homogeneity
  // (theory.md section 6) the written von Mises stress and displacement,
  // times their scales over the pressure, are those of pressure 1 to the
  // floats' rounding (before: solved as given, inf and subnormal fields).
  void
  check_fields_beyond_float_range(ConditionalOStream &out)
  {
    std::array<double, 2> reference_stress, reference_displacement;
    for (const std::string pressure : {"1", "1e40", "1e-40"})
      {
        const ProgramRun run(
          one_hdf5_cycle("output-hdf5-pressure-" + pressure,
                         {"Scene/Blocks/Pressure", pressure}));
        const double P = run.summary.value("load_scale", 1.);
        const double D = run.summary.value("displacement_scale", P);
        const double p = std::stod(pressure);
        out << "Format = hdf5, pressure " << pressure << ": load scale 2^"
            << std::log2(P) << ", displacement scale 2^" << std::log2(D)
            << std::endl;
        for (unsigned int b = 0; b < 2; ++b)
          {
            const std::string directory = run.parameters.output.directory;
            const double      stress =
              written_maximum(directory, b, 0, "von_mises") * P / p;
            const double displacement =
              written_maximum(directory, b, 0) * D / p;
            if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
              continue;
            if (pressure == "1")
              {
                reference_stress[b]       = stress;
                reference_displacement[b] = displacement;
                continue;
              }
            const double stress_difference =
              std::abs(stress / reference_stress[b] - 1);
            const double displacement_difference =
              std::abs(displacement / reference_displacement[b] - 1);
            out << "  body " << b + 1
                << ": written max von Mises and |u| times scale / pressure "
                   "as pressure 1 to 2.4e-7: "
                << (stress_difference <= 2.4e-7 &&
                        displacement_difference <= 2.4e-7 ?
                      "yes" :
                      "no")
                << std::endl;
            AssertThrow(std::isfinite(stress) && stress_difference <= 2.4e-7 &&
                          displacement_difference <= 2.4e-7,
                        ExcMessage("fields not written within the floats"));
          }
      }
  }

  void
  check_write_cycles(const std::string  &format,
                     const std::string  &write_cycles,
                     ConditionalOStream &out)
  {
    out << "Format = " << format << ", Write cycles = " << write_cycles
        << std::endl;
    const ProgramRun run(
      blocks(format, write_cycles, "output-" + format + "-" + write_cycles));
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) > 0)
      return;
    const std::string directory = run.parameters.output.directory;
    // The files, with the rank number of VTU pieces left out so that any
    // number of ranks prints the same.
    std::set<std::string> files;
    for (const auto &name : files_in(directory))
      files.insert(std::regex_replace(name,
                                      std::regex("(_[0-9]{3})\\.[0-9]+\\.vtu$"),
                                      "$1.R.vtu"));
    out << "  files:";
    for (const auto &name : files)
      out << ' ' << name;
    out << std::endl;
    const unsigned int n_cycles = run.summary["cycles"].size();
    AssertThrow(n_cycles == 2, ExcMessage("summary.json lacks a cycle"));
    for (unsigned int c = 0; c < 2; ++c)
      AssertThrow(files.count("contact_" + Utilities::int_to_string(c, 3) +
                              ".csv") == 1,
                  ExcMessage("a contact CSV is missing"));
    const std::string index = format == "vtu" ? ".pvd" : ".xdmf";
    for (const std::string base : {"body-1", "body-2", "contact"})
      {
        const bool has_index = files.count(base + index) == 1;
        const bool has_first = files.count(base + "_000.h5") +
                                 files.count(base + "_000.pvtu") +
                                 files.count(base + "_000.vtu") >
                               0;
        const bool has_last = files.count(base + "_001.h5") +
                                files.count(base + "_001.pvtu") +
                                files.count(base + "_001.vtu") >
                              0;
        if (write_cycles == "none")
          {
            AssertThrow(!has_index && !has_first && !has_last,
                        ExcMessage("fields written with Write cycles = none"));
          }
        else
          {
            const unsigned int n_records =
              count(read_text(directory + "/" + base + index),
                    format == "vtu" ? "<DataSet" : "<Grid Name=\"mesh\"");
            out << "  " << base << index << ": " << n_records << " record(s)"
                << std::endl;
            AssertThrow(!has_first && has_last && n_records == 1,
                        ExcMessage("Write cycles = last wrote other than "
                                   "the last cycle"));
          }
      }
  }

  // The fields a .pvtu lists, in order.
  std::vector<std::string>
  pvtu_field_names(const std::string &path)
  {
    const std::string        text = read_text(path);
    const std::regex         name("<PDataArray[^>]*Name=\"([^\"]+)\"");
    std::vector<std::string> names;
    for (std::sregex_iterator m(text.begin(), text.end(), name), end; m != end;
         ++m)
      names.push_back((*m)[1]);
    return names;
  }

  // Output/Write smoothed stress: zz's recovered stress is written only
  // when asked; the other fields are the same either way.
  void
  check_smoothed_stress(ConditionalOStream &out)
  {
    for (const std::string write : {"false", "true"})
      {
        Settings settings =
          blocks("vtu", "last", "output-smoothed-stress-" + write);
        settings.push_back({"Output/Write smoothed stress", write});
        settings.push_back({"Adaptation/Number of cycles", "1"});
        const ProgramRun run(settings);
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) > 0)
          continue;
        const std::vector<std::string> names = pvtu_field_names(
          run.parameters.output.directory + "/body-1_000.pvtu");
        out << "Write smoothed stress = " << write << ": fields";
        for (const auto &n : names)
          out << ' ' << n;
        out << std::endl;
        const bool smoothed =
          std::count(names.begin(), names.end(), "smoothed_stress_xx") +
            std::count(names.begin(), names.end(), "smoothed_stress_yy") +
            std::count(names.begin(), names.end(), "smoothed_stress_xy") ==
          3;
        AssertThrow(smoothed == (write == "true") &&
                      std::count(names.begin(),
                                 names.end(),
                                 "error_indicator") == 1,
                    ExcMessage("Write smoothed stress = " + write +
                               " wrote the wrong fields"));
      }
  }
} // namespace



int
main(int argc, char **argv)
{
  prefer_mpi_io_without_named_semaphores();
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::setprecision(6);

  check_hdf5(out);
  check_write_cycles("vtu", "last", out);
  check_write_cycles("hdf5", "last", out);
  check_write_cycles("vtu", "none", out);
  check_hdf5_quadratic_triangles(out);
  check_hdf5_scaled_problem(out);
  check_fields_beyond_float_range(out);
  check_smoothed_stress(out);
}
