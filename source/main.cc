// coulomb-adapt: adaptive finite element analysis of 2D frictional contact.
// main() only reads the command line and the parameters, runs, and turns
// every error into a message and a non-zero exit code.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/app/command_line.h>
#include <coulomb_adapt/app/input_file_paths.h>
#include <coulomb_adapt/app/one_node_messaging.h>
#include <coulomb_adapt/app/parallel_file_io.h>
#include <coulomb_adapt/app/small_block_allocation.h>
#include <coulomb_adapt/app/two_body_problem.h>
#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/output/file_writer.h>

#include <fstream>
#include <iostream>
#include <memory>

int
main(int argc, char *argv[])
{
  using namespace coulomb_adapt;
  // Threads: as many as the cores left to this rank (one per core in all;
  // DEAL_II_NUM_THREADS limits them). They run the cells of the cre
  // estimator and deal.II's own threaded loops (DataOut).
  // Before MPI_Init: ranks all on one node skip Open MPI's probing of
  // network layers they never use (app/one_node_messaging.h).
  prefer_shared_memory_messaging_on_one_node();
  // Small blocks freed without glibc's fastbins: deal.II's output spent a
  // third of its time merging them (app/small_block_allocation.h).
  turn_off_malloc_fastbins();
  // Parallel HDF5 files through ROMIO: OMPIO's named semaphores, left
  // locked by a killed run, hang later runs (app/parallel_file_io.h).
  prefer_mpi_io_without_named_semaphores();
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const bool is_root = Utilities::MPI::this_mpi_process(comm) == 0;

  try
    {
      const CommandLine command_line = parse_command_line(argc, argv);
      ParameterHandler  prm;
      TwoBodyProblem::declare_parameters(prm);

      if (command_line.help)
        {
          if (is_root)
            std::cout << usage();
          return 0;
        }
      // With a file or -s, --print-parameters prints the values they give
      // (and stops on an error in them, like a run would).
      read_parameters(command_line, prm);
      if (command_line.print_parameters)
        {
          if (is_root)
            prm.print_parameters(std::cout, ParameterHandler::PRM);
          return 0;
        }

      // Errors in values (and in the files the values name) are reported
      // with where the values came from.
      const std::string source =
        (command_line.parameter_file.empty() ?
           std::string("the default parameters") :
           "parameter file '" + command_line.parameter_file + "'") +
        (command_line.overrides.empty() ? "" : " with -s overrides");
      Parameters                      parameters;
      std::unique_ptr<TwoBodyProblem> problem;
      try
        {
          parameters.parse_parameters(prm);
          prepare_output_directory(parameters.output.directory, comm);
          problem = std::make_unique<TwoBodyProblem>(
            comm, parameters, prm, command_line.parameter_file);
        }
      catch (const ParameterError &e)
        {
          throw ParameterError("in " + source + ": " + e.what());
        }

      // A bare command runs the defaults; say so, since a user who typed
      // it may have expected the usage text instead.
      if (is_root && command_line.parameter_file.empty() &&
          command_line.overrides.empty())
        std::cout << "coulomb-adapt: no parameter file given: running the "
                     "default parameters (the seed's example is "
                     "prm/blocks.prm; 'coulomb-adapt --help' for usage)"
                  << std::endl;
      make_input_files_absolute(prm);
      write_file(comm,
                 parameters.output.directory + "/parameters.prm",
                 [&](std::ostream &resolved) {
                   prm.print_parameters(resolved, ParameterHandler::ShortPRM);
                 });
      problem->run();
    }
  catch (const ParameterError &e)
    {
      if (is_root)
        std::cerr << "coulomb-adapt: error: " << e.what() << std::endl;
      return 1;
    }
  catch (const std::exception &e)
    {
      if (is_root)
        std::cerr << "coulomb-adapt: error: " << user_message(e) << std::endl;
      return 1;
    }
  return 0;
}
