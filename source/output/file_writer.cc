#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <coulomb_adapt/output/file_writer.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace coulomb_adapt
{
  using namespace dealii;

  void
  write_file(const MPI_Comm                            comm,
             const std::string &                       path,
             const std::function<void(std::ostream &)> &write)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        const std::string temporary = path + ".tmp";
        errno                       = 0;
        {
          std::ofstream out(temporary);
          if (!out)
            error = "cannot open it for writing";
          else
            {
              write(out);
              out.flush();
              if (!out)
                error = "writing failed";
            }
        }
        if (!error.empty())
          {
            if (errno != 0)
              error += std::string(" (") + std::strerror(errno) + ")";
            std::remove(temporary.c_str());
          }
        else if (std::rename(temporary.c_str(), path.c_str()) != 0)
          {
            error = std::string("cannot replace it (") +
                    std::strerror(errno) + ")";
            std::remove(temporary.c_str());
          }
      }
    error = Utilities::MPI::broadcast(comm, error, 0);
    AssertThrow(error.empty(),
                ExcMessage("output file '" + path + "': " + error));
  }
} // namespace coulomb_adapt
