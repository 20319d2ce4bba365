#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <coulomb_adapt/solvers/symmetric_direct_solver.h>

#include <Epetra_CrsMatrix.h>
#include <dmumps_c.h>

#include <numeric>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    // MUMPS's 1-based control arrays.
    int &
    icntl(DMUMPS_STRUC_C &id, const unsigned int i)
    {
      return id.icntl[i - 1];
    }



    // The lower triangle of the locally owned rows of @p A, 1-based global
    // indices (MUMPS's distributed assembled entry, ICNTL(18) = 3).
    struct LowerTriangle
    {
      std::vector<MUMPS_INT> rows, columns;
      std::vector<double>    values;
    };

    LowerTriangle
    owned_lower_triangle(const Epetra_CrsMatrix &matrix)
    {
      LowerTriangle lower;
      for (int i = 0; i < matrix.NumMyRows(); ++i)
        {
          int     n       = 0;
          double *values  = nullptr;
          int    *indices = nullptr;
          matrix.ExtractMyRowView(i, n, values, indices);
          const long long row = matrix.RowMap().GID64(i);
          for (int k = 0; k < n; ++k)
            {
              const long long column = matrix.ColMap().GID64(indices[k]);
              if (column <= row)
                {
                  lower.rows.push_back(static_cast<MUMPS_INT>(row + 1));
                  lower.columns.push_back(static_cast<MUMPS_INT>(column + 1));
                  lower.values.push_back(values[k]);
                }
            }
        }
      return lower;
    }



    // A distributed vector's values on rank 0, in the order of the global
    // indices, and how many each rank owns (rank 0 only).
    struct RankZeroVector
    {
      std::vector<double> values;
      std::vector<int>    counts;
    };

    // The ranks own consecutive ranges of rows in rank order (deal.II's
    // DoF numbering), so rank 0 concatenates the parts.
    RankZeroVector
    gather_on_rank_zero(const TrilinosWrappers::MPI::Vector &v)
    {
      const MPI_Comm     comm       = v.get_mpi_communicator();
      const unsigned int rank       = Utilities::MPI::this_mpi_process(comm);
      const IndexSet     owned_rows = v.locally_owned_elements();
      const std::vector<types::global_dof_index> rows_per_rank =
        Utilities::MPI::all_gather(comm, owned_rows.n_elements());
      const types::global_dof_index first_row =
        std::accumulate(rows_per_rank.begin(),
                        rows_per_rank.begin() + rank,
                        types::global_dof_index(0));
      AssertThrow(owned_rows.n_elements() == 0 ||
                    (owned_rows.is_contiguous() &&
                     owned_rows.nth_index_in_set(0) == first_row),
                  ExcMessage(
                    "solve_symmetric_positive_definite() needs the "
                    "rows owned in consecutive ranges in rank order."));
      const std::vector<std::vector<double>> parts =
        Utilities::MPI::gather(comm,
                               std::vector<double>(v.begin(), v.end()),
                               0);
      RankZeroVector gathered;
      for (const auto &part : parts)
        {
          gathered.values.insert(gathered.values.end(),
                                 part.begin(),
                                 part.end());
          gathered.counts.push_back(static_cast<int>(part.size()));
        }
      return gathered;
    }



    // The inverse of gather_on_rank_zero(): each rank's part into @p v.
    void
    scatter_from_rank_zero(const RankZeroVector          &gathered,
                           TrilinosWrappers::MPI::Vector &v)
    {
      std::vector<int> starts(gathered.counts.size(), 0);
      for (std::size_t r = 1; r < starts.size(); ++r)
        starts[r] = starts[r - 1] + gathered.counts[r - 1];
      std::vector<double> owned(v.locally_owned_size());
      const int           ierr = MPI_Scatterv(gathered.values.data(),
                                    gathered.counts.data(),
                                    starts.data(),
                                    MPI_DOUBLE,
                                    owned.data(),
                                    static_cast<int>(owned.size()),
                                    MPI_DOUBLE,
                                    0,
                                    v.get_mpi_communicator());
      AssertThrowMPI(ierr);
      std::copy(owned.begin(), owned.end(), v.begin());
      v.compress(VectorOperation::insert);
    }



    // What a negative INFOG(1) means, for the message (MUMPS's user guide,
    // section "Error diagnostics").
    std::string
    mumps_error_meaning(const int code)
    {
      switch (code)
        {
          case -10:
            return "the matrix is numerically singular";
          case -13:
            return "MUMPS could not allocate its workspace";
          case -8:
          case -9:
          case -14:
          case -15:
            return "MUMPS's workspace was too small";
          default:
            return "see MUMPS's user guide";
        }
    }



    void
    call_mumps(DMUMPS_STRUC_C &id, const int job)
    {
      id.job = job;
      dmumps_c(&id);
      AssertThrow(id.infog[0] >= 0,
                  ExcMessage("MUMPS failed on a symmetric positive definite "
                             "system (job " +
                             std::to_string(job) +
                             "): INFOG(1) = " + std::to_string(id.infog[0]) +
                             ", INFOG(2) = " + std::to_string(id.infog[1]) +
                             ": " + mumps_error_meaning(id.infog[0]) + "."));
    }
  } // namespace



  void
  solve_symmetric_positive_definite(const TrilinosWrappers::SparseMatrix &A,
                                    TrilinosWrappers::MPI::Vector        &x,
                                    const TrilinosWrappers::MPI::Vector  &b)
  {
    const MPI_Comm      comm  = b.get_mpi_communicator();
    const unsigned int  rank  = Utilities::MPI::this_mpi_process(comm);
    const MUMPS_INT     n     = static_cast<MUMPS_INT>(A.m());
    const LowerTriangle lower = owned_lower_triangle(A.trilinos_matrix());

    DMUMPS_STRUC_C id{};
    id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    id.par          = 1; // rank 0 factorises too
    id.sym          = 1; // positive definite: LDL^T without pivoting
    call_mumps(id, -1);
    // Quiet: failures are reported through INFOG(1) above.
    icntl(id, 1)  = -1;
    icntl(id, 2)  = -1;
    icntl(id, 3)  = -1;
    icntl(id, 4)  = 0;
    icntl(id, 18) = 3; // distributed assembled matrix
    icntl(id, 28) = 1; // sequential analysis
    // MUMPS's own choice of ordering (PORD in Debian's build, which has
    // no METIS or SCOTCH in MUMPS): on the 130,275 parameters of the
    // 26,724-DoF blocks, 3.8e9 flops against 4.2e9 with METIS's nested
    // dissection given as perm_in, in the same time with the analysis.
    icntl(id, 7) = 7;
    id.n         = n;
    id.nnz_loc   = static_cast<MUMPS_INT8>(lower.rows.size());
    id.irn_loc   = const_cast<MUMPS_INT *>(lower.rows.data());
    id.jcn_loc   = const_cast<MUMPS_INT *>(lower.columns.data());
    id.a_loc     = const_cast<double *>(lower.values.data());

    // b on rank 0 (MUMPS's centralised right hand side), solved in place.
    RankZeroVector rhs = gather_on_rank_zero(b);
    id.rhs             = rank == 0 ? rhs.values.data() : nullptr;

    try
      {
        call_mumps(id, 4); // analysis and factorisation
        call_mumps(id, 3); // solve
      }
    catch (...)
      {
        id.job = -2;
        dmumps_c(&id);
        throw;
      }
    id.job = -2;
    dmumps_c(&id);

    scatter_from_rank_zero(rhs, x);
  }
} // namespace coulomb_adapt
