// VTU output in pieces (output/vtu_pieces.h, file_writer.h): a body's
// patches split into pieces that are written concurrently must hold
// exactly what one file per rank held, and the .pvtu record must list
// every piece of every rank.
//
// On a distributed 16 x 16 quadrilateral mesh with the field x + 2y (Q1),
// for 1, 2 and 3 pieces per rank:
//  - take_pieces(): the pieces' patches, concatenated, are the patches of
//    an ordinary DataOut (vertices and data, entry for entry), in pieces
//    whose sizes differ by at most one; names and vector ranges are kept;
//  - write_vtu_pieces_with_pvtu_record(): the record lists (ranks x
//    pieces) files named BASE_CCC.I.vtu, I in rank order; every listed
//    file exists, their NumberOfCells add up to the mesh's cells, and no
//    NAME.tmp is left.
// n_vtu_pieces(): one piece per thread, but none below the minimum size.
// The counts printed are sums over the ranks: 1 and 2 ranks print the
// same apart from the pieces listed.

#include <deal.II/base/function_parser.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/output/file_writer.h>
#include <coulomb_adapt/output/vtu_pieces.h>

#include "test_utilities.h"

#include <algorithm>
#include <filesystem>
#include <regex>

using namespace coulomb_adapt;

namespace
{
  using Patch = DataOutBase::Patch<2, 2>;

  bool
  same_patch(const Patch &a, const Patch &b)
  {
    bool same = a.data.n_rows() == b.data.n_rows() &&
                a.data.n_cols() == b.data.n_cols() &&
                std::equal(std::begin(a.vertices),
                           std::end(a.vertices),
                           std::begin(b.vertices));
    for (unsigned int i = 0; same && i < a.data.n_rows(); ++i)
      for (unsigned int j = 0; same && j < a.data.n_cols(); ++j)
        same = a.data(i, j) == b.data(i, j);
    return same;
  }
} // namespace

int
main(int argc, char *argv[])
{
  // Two threads per rank: the pieces are written concurrently.
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 2);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int               rank = Utilities::MPI::this_mpi_process(comm);

  parallel::distributed::Triangulation<2> tria(comm);
  GridGenerator::hyper_cube(tria);
  tria.refine_global(4);
  DoFHandler<2> dof_handler(tria);
  dof_handler.distribute_dofs(FE_Q<2>(1));
  LinearAlgebra::distributed::Vector<double> field(
    dof_handler.locally_owned_dofs(),
    DoFTools::extract_locally_relevant_dofs(dof_handler),
    comm);
  VectorTools::interpolate(dof_handler, FunctionParser<2>("x + 2*y"), field);
  field.update_ghost_values();

  const std::string directory = "pieces";
  if (rank == 0)
    std::filesystem::create_directories(directory);
  MPI_Barrier(comm);

  DataOut<2> whole;
  whole.attach_dof_handler(dof_handler);
  whole.add_data_vector(field, "f");
  whole.build_patches();
  const std::vector<Patch> reference = whole.get_patches();

  bool all_ok = true;
  for (unsigned int n_pieces = 1; n_pieces <= 3; ++n_pieces)
    {
      PieceableDataOut data_out;
      data_out.attach_dof_handler(dof_handler);
      data_out.add_data_vector(field, "f");
      data_out.build_patches();
      const std::vector<PatchPiece> pieces = data_out.take_pieces(n_pieces);

      std::vector<Patch> joined;
      std::size_t        smallest = reference.size(), largest = 0;
      bool               names_kept = true;
      for (const PatchPiece &piece : pieces)
        {
          joined.insert(joined.end(),
                        piece.get_patches().begin(),
                        piece.get_patches().end());
          smallest   = std::min(smallest, piece.get_patches().size());
          largest    = std::max(largest, piece.get_patches().size());
          names_kept = names_kept && piece.get_dataset_names() ==
                                       std::vector<std::string>{"f"};
        }
      unsigned int n_different = joined.size() != reference.size();
      for (unsigned int i = 0; n_different == 0 && i < joined.size(); ++i)
        n_different += !same_patch(joined[i], reference[i]);
      const bool split_ok = pieces.size() == n_pieces && largest - smallest <= 1 &&
                            names_kept && data_out.get_patches().empty();
      n_different = Utilities::MPI::sum(n_different, comm);
      const unsigned int n_split_wrong =
        Utilities::MPI::sum(static_cast<unsigned int>(!split_ok), comm);

      const std::string record = write_vtu_pieces_with_pvtu_record(
        comm, pieces, directory, "body", n_pieces);
      MPI_Barrier(comm);
      // Rank 0 checks the files of all ranks.
      unsigned int n_listed = 0, n_missing = 0, n_misnamed = 0,
                   n_cells = 0, n_tmp = 0;
      if (rank == 0)
        {
          const std::string text = testing::read_text(directory + "/" + record);
          const std::regex  source("<Piece Source=\"([^\"]+)\"/>");
          for (auto m = std::sregex_iterator(text.begin(), text.end(), source);
               m != std::sregex_iterator();
               ++m)
            {
              const std::string name = (*m)[1];
              n_misnamed += name != "body_00" + std::to_string(n_pieces) + "." +
                                      std::to_string(n_listed) + ".vtu";
              ++n_listed;
              const std::string piece = testing::read_text(directory + "/" + name);
              std::smatch       cells;
              if (std::regex_search(piece,
                                    cells,
                                    std::regex("NumberOfCells=\"([0-9]+)\"")))
                n_cells += std::stoul(cells[1]);
              else
                ++n_missing;
            }
          for (const auto &entry :
               std::filesystem::directory_iterator(directory))
            n_tmp += entry.path().extension() == ".tmp";
        }
      n_listed   = Utilities::MPI::broadcast(comm, n_listed, 0);
      n_missing  = Utilities::MPI::broadcast(comm, n_missing, 0);
      n_misnamed = Utilities::MPI::broadcast(comm, n_misnamed, 0);
      n_cells    = Utilities::MPI::broadcast(comm, n_cells, 0);
      n_tmp      = Utilities::MPI::broadcast(comm, n_tmp, 0);
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);

      out << n_pieces << " piece(s) per rank: patches that differ "
          << n_different << ", ranks with a wrong split " << n_split_wrong
          << "; record " << record << " lists " << n_listed / n_ranks
          << " file(s) per rank, misnamed " << n_misnamed << ", missing "
          << n_missing << ", cells in the files " << n_cells
          << " (mesh: " << tria.n_global_active_cells() << "), .tmp left "
          << n_tmp << std::endl;
      all_ok = all_ok && n_different == 0 && n_split_wrong == 0 &&
               n_listed == n_ranks * n_pieces && n_misnamed == 0 &&
               n_missing == 0 && n_cells == tria.n_global_active_cells() &&
               n_tmp == 0;
    }

  // One piece per thread, each at least the minimum size.
  const std::vector<std::array<std::size_t, 4>> rule = {
    {{0, 2, 16384, 1}},
    {{20000, 2, 16384, 1}},
    {{40000, 2, 16384, 2}},
    {{40000, 1, 16384, 1}},
    {{100000, 8, 16384, 6}},
    {{100000, 4, 16384, 4}},
    {{10, 4, 3, 3}}};
  for (const auto &[n_patches, n_threads, minimum, expected] : rule)
    {
      const unsigned int n = n_vtu_pieces(n_patches, n_threads, minimum);
      out << "n_vtu_pieces(" << n_patches << " patches, " << n_threads
          << " threads, at least " << minimum << "): " << n << std::endl;
      all_ok = all_ok && n == expected;
    }
  AssertThrow(all_ok, ExcMessage("the VTU pieces are wrong"));
  return 0;
}
