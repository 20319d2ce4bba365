#include <deal.II/base/partitioner.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/vector_memory.h>

#include <coulomb_adapt/solvers/linear_solver.h>

#include <Epetra_MultiVector.h>
#include <Epetra_Operator.h>
#include <Epetra_RowMatrix.h>
#include <Epetra_Vector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>

#ifdef __GLIBC__
#  include <malloc.h>
#endif

namespace coulomb_adapt
{
  namespace
  {
    LinearSolverReport
    solve_direct(const TrilinosWrappers::SparseMatrix &A,
                 TrilinosWrappers::MPI::Vector        &x,
                 const TrilinosWrappers::MPI::Vector  &b,
                 const std::string                    &package)
    {
      SolverControl                                  control(1, 0);
      TrilinosWrappers::SolverDirect::AdditionalData data(false, package);
      TrilinosWrappers::SolverDirect                 solver(control, data);
      solver.initialize(A);
      solver.solve(x, b);
      // One step of iterative refinement with the same factorisation (a
      // back substitution): on badly scaled systems (the contact system of
      // bodies with E1/E2 = 1e3) the first solve's residual limits the
      // accuracy of the multipliers, which are differences of nodal forces.
      TrilinosWrappers::MPI::Vector residual(b);
      A.vmult(residual, x);
      residual.sadd(-1., 1., b);
      TrilinosWrappers::MPI::Vector correction(b);
      solver.solve(correction, residual);
      x += correction;
      return {"direct (" + package + ")", 1};
    }



    LinearSolverReport
    solve_amg(const TrilinosWrappers::SparseMatrix   &A,
              TrilinosWrappers::MPI::Vector          &x,
              const TrilinosWrappers::MPI::Vector    &b,
              const std::vector<std::vector<double>> &near_null_space,
              const parameters::LinearSolver         &settings,
              const bool                              symmetric)
    {
      ElasticityAMG amg;
      amg.initialize(A, near_null_space);
      return solve_krylov(A, x, b, amg.preconditioner, settings, symmetric);
    }
  } // namespace



  void
  return_freed_heap_memory()
  {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
  }



  namespace
  {
    // The owned rows of a deal.II matrix or of an Epetra row matrix.
    unsigned int
    n_owned_rows(const TrilinosWrappers::SparseMatrix &A)
    {
      return A.local_size();
    }
    unsigned int
    n_owned_rows(const Epetra_RowMatrix &A)
    {
      return A.NumMyRows();
    }
    unsigned int
    owned_row_index(const TrilinosWrappers::SparseMatrix &A,
                    const types::global_dof_index         i)
    {
      Assert(A.locally_owned_range_indices().is_element(i), ExcInternalError());
      return A.locally_owned_range_indices().index_within_set(i);
    }
    unsigned int
    owned_row_index(const Epetra_RowMatrix &A, const types::global_dof_index i)
    {
      const int local = A.RowMatrixRowMap().LID(static_cast<int>(i));
      Assert(local >= 0, ExcInternalError());
      return local;
    }



    template <typename Matrix>
    void
    setup_elasticity_amg(
      TrilinosWrappers::PreconditionAMG          &preconditioner,
      const Matrix                               &A,
      const std::vector<std::vector<double>>     &near_null_space,
      const std::vector<types::global_dof_index> &zero_rows)
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      // Smoothed aggregation for elasticity, also for the (nearly
      // symmetric) eliminated contact system and a pinned floating body:
      // ML's non-symmetric variant took 2.6x longer to set up on the
      // contact system and saved no GMRES iteration (hertz, 140,316 DoFs:
      // 46 iterations either way).
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      // Drop only very weak connections when aggregating: with 0.02 the
      // GMRES iterations on the eliminated contact system grew from 39 to
      // 64 between 1.7e5 and 6.6e5 DoFs (blocks, mu = 0.3); with 1e-4 they
      // are 23 and 25 (hertz at 5.6e5 DoFs: 36 instead of 70). Elasticity
      // on uniform meshes is indifferent (15 and 13 CG iterations at 1e6
      // DoFs either way).
      data.aggregation_threshold = 1e-4;

      // deal.II 9.4 can only hand ML constant modes; the rotation needs the
      // mode values, so we fill ML's null space entries ourselves.
      Teuchos::ParameterList              ml_parameters;
      std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
      data.set_parameters(ml_parameters, unused_constant_modes, A);

      const unsigned int n_modes = near_null_space.size();
      const unsigned int n_local = n_owned_rows(A);
      // ML copies the mode values during the setup (its aggregation object
      // keeps its own null space), so this buffer is needed only until the
      // hierarchy is built.
      std::vector<double> modes(n_modes * n_local, 0.);
      for (unsigned int m = 0; m < n_modes; ++m)
        {
          AssertDimension(near_null_space[m].size(), n_local);
          std::copy(near_null_space[m].begin(),
                    near_null_space[m].end(),
                    modes.begin() + m * n_local);
          for (const auto i : zero_rows)
            modes[m * n_local + owned_row_index(A, i)] = 0.;
        }
      // Aggregate the two displacement components of a node together:
      // without this ML treats every DoF as its own PDE and its iteration
      // count grows with refinement (benchmarks/elasticity: 41 instead of
      // 15 iterations at 1e6 DoFs).
      ml_parameters.set("PDE equations", 2);
      if (n_modes > 0)
        {
          ml_parameters.set("null space: type", "pre-computed");
          ml_parameters.set("null space: dimension", static_cast<int>(n_modes));
          ml_parameters.set("null space: vectors", modes.data());
        }

      preconditioner.initialize(A, ml_parameters);
      // The setup's products (A P, R A P, several times the size of A) are
      // freed now: their pages back before the Krylov basis is allocated.
      return_freed_heap_memory();
    }
  } // namespace



  void
  ElasticityAMG::initialize(
    const TrilinosWrappers::SparseMatrix       &A,
    const std::vector<std::vector<double>>     &near_null_space,
    const std::vector<types::global_dof_index> &zero_rows)
  {
    setup_elasticity_amg(preconditioner, A, near_null_space, zero_rows);
  }



  void
  initialize_elasticity_amg(
    ElasticityAMG                              &amg,
    const Epetra_RowMatrix                     &A,
    const std::vector<std::vector<double>>     &near_null_space,
    const std::vector<types::global_dof_index> &zero_rows)
  {
    setup_elasticity_amg(amg.preconditioner, A, near_null_space, zero_rows);
  }



  namespace
  {
    // GMRES's vectors: deal.II's own, whose operations run on deal.II's
    // threads with a fused add_and_dot (the Gram-Schmidt step, one pass
    // over the vectors instead of Epetra's Update and Dot). Their owned
    // entries are stored in the order of the Epetra maps' local indices
    // (both ascending in the global index), so the matrix and the
    // preconditioner act on them through Epetra views, without copies;
    // their own global numbering is a contiguous stand-in (krylov()).
    // Measured (benchmarks/adaptive_run, 29th session): the
    // orthogonalisation of a 50-step GMRES solve at 1.7e5 DoFs takes
    // 0.26 s with Epetra's vectors and 0.11 s with these on two threads.
    // deal.II cuts its reductions into chunks whose number depends on
    // the number of threads, so the iterates are reproducible for a given
    // number of threads and agree to round-off between numbers
    // (tests/threaded_products), as the assembly does. CG keeps Epetra's
    // vectors: it has no basis to orthogonalise, and its iterates stay
    // those of before to the bit.
    using GMRESVector = LinearAlgebra::distributed::Vector<double>;

    Epetra_Vector
    epetra_view(const Epetra_BlockMap &map, const GMRESVector &v)
    {
      AssertThrow(static_cast<std::size_t>(map.NumMyElements()) ==
                    v.locally_owned_size(),
                  ExcDimensionMismatch(map.NumMyElements(),
                                       v.locally_owned_size()));
      return Epetra_Vector(View, map, const_cast<double *>(v.begin()));
    }



    // An Epetra operator as deal.II's solvers take a matrix.
    struct EpetraProduct
    {
      void
      vmult(TrilinosWrappers::MPI::Vector       &dst,
            const TrilinosWrappers::MPI::Vector &src) const
      {
        const int error = A.Apply(src.trilinos_vector(), dst.trilinos_vector());
        AssertThrow(error == 0, ExcTrilinosError(error));
      }

      void
      vmult(GMRESVector &dst, const GMRESVector &src) const
      {
        const Epetra_Vector x     = epetra_view(A.OperatorDomainMap(), src);
        Epetra_Vector       y     = epetra_view(A.OperatorRangeMap(), dst);
        const int           error = A.Apply(x, y);
        AssertThrow(error == 0, ExcTrilinosError(error));
      }

      const Epetra_Operator &A;
    };



    // The owned entries of @p v in a GMRES vector on @p layout.
    GMRESVector
    gmres_copy(const TrilinosWrappers::MPI::Vector                      &v,
               const std::shared_ptr<const Utilities::MPI::Partitioner> &layout)
    {
      GMRESVector copy(layout);
      std::copy(v.begin(), v.end(), copy.begin());
      return copy;
    }



    // The solvers take their vectors from deal.II's static pool, which
    // keeps them after the solve: GMRES's Krylov basis (one vector per
    // iteration) would stay allocated through the next Newton step's
    // matrix products, where the contact solve has its peak. Returned
    // when the solver is done with them.
    template <typename VectorType>
    void
    release_solver_vectors()
    {
      GrowingVectorMemory<VectorType>::release_unused_memory();
      return_freed_heap_memory();
    }



    LinearSolverReport
    krylov(const Epetra_Operator                    &A,
           TrilinosWrappers::MPI::Vector            &x,
           const TrilinosWrappers::MPI::Vector      &b,
           const TrilinosWrappers::PreconditionBase &preconditioner,
           const parameters::LinearSolver           &settings,
           const bool                                symmetric)
    {
      SolverControl       control(settings.max_iterations,
                            settings.relative_tolerance * b.l2_norm());
      const EpetraProduct product{A};
      // The pool is emptied however the solve ends: a caller that catches
      // the non-convergence (a tighter repeat, a fresh AMG hierarchy)
      // solves again right away.
      if (symmetric)
        {
          try
            {
              SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
              cg.solve(product, x, b, preconditioner);
            }
          catch (...)
            {
              release_solver_vectors<TrilinosWrappers::MPI::Vector>();
              throw;
            }
          release_solver_vectors<TrilinosWrappers::MPI::Vector>();
          return {"cg+amg", control.last_step()};
        }
      // Right preconditioning: GMRES then stops on the true residual. With
      // left preconditioning it stopped on the preconditioned one, and on
      // the contact system the true residual stayed large enough to leave
      // the complementarity residual at 3e-4 (hertz, 3.6e4 DoFs).
      // A contiguous stand-in numbering of the owned entries, in their
      // order: the contact system's owned set is not contiguous (each rank
      // owns a range of each body's DoFs), which deal.II's partitioner
      // does not take, and GMRES needs only the local entries and global
      // sums.
      const auto layout = std::make_shared<const Utilities::MPI::Partitioner>(
        x.locally_owned_size(), 0, x.get_mpi_communicator());
      GMRESVector       gmres_x = gmres_copy(x, layout);
      const GMRESVector gmres_b = gmres_copy(b, layout);
      const auto        finish  = [&] {
        // The last iterate, also when the solve failed (as deal.II's
        // solvers leave it in x).
        std::copy(gmres_x.begin(), gmres_x.end(), x.begin());
        release_solver_vectors<GMRESVector>();
      };
      try
        {
          SolverGMRES<GMRESVector> gmres(
            control,
            SolverGMRES<GMRESVector>::AdditionalData(
              100, /*right_preconditioning=*/true));
          gmres.solve(product, gmres_x, gmres_b, preconditioner);
        }
      catch (...)
        {
          finish();
          throw;
        }
      finish();
      return {"gmres+amg", control.last_step()};
    }
  } // namespace



  LinearSolverReport
  solve_krylov(const TrilinosWrappers::SparseMatrix     &A,
               TrilinosWrappers::MPI::Vector            &x,
               const TrilinosWrappers::MPI::Vector      &b,
               const TrilinosWrappers::PreconditionBase &preconditioner,
               const parameters::LinearSolver           &settings,
               const bool                                symmetric)
  {
    return krylov(
      A.trilinos_matrix(), x, b, preconditioner, settings, symmetric);
  }



  LinearSolverReport
  solve_krylov(const Epetra_Operator                    &A,
               TrilinosWrappers::MPI::Vector            &x,
               const TrilinosWrappers::MPI::Vector      &b,
               const TrilinosWrappers::PreconditionBase &preconditioner,
               const parameters::LinearSolver           &settings,
               const bool                                symmetric)
  {
    return krylov(A, x, b, preconditioner, settings, symmetric);
  }



  LinearSolverReport
  solve_linear_system(const TrilinosWrappers::SparseMatrix   &A,
                      TrilinosWrappers::MPI::Vector          &x,
                      const TrilinosWrappers::MPI::Vector    &b,
                      const std::vector<std::vector<double>> &near_null_space,
                      const parameters::LinearSolver         &settings,
                      const bool                              symmetric)
  {
    const bool direct = settings.type == LinearSolverType::direct ||
                        (settings.type == LinearSolverType::automatic &&
                         A.m() <= settings.max_dofs_for_direct);
    if (direct)
      return solve_direct(A, x, b, settings.direct_solver);
    return solve_amg(A, x, b, near_null_space, settings, symmetric);
  }
  std::string
  iteration_limit_message(const std::string &system,
                          const std::string &solver_name,
                          const unsigned int last_step,
                          const double       last_residual)
  {
    std::ostringstream s;
    s << system << ": the iterative linear solver"
      << (solver_name.empty() ? "" : " (" + solver_name + ")")
      << " did not converge in " << last_step
      << " iterations (the limit 'Linear solver/Maximum iterations'; "
         "residual "
      << last_residual
      << "). Raise 'Linear solver/Maximum iterations', or use 'Linear "
         "solver/Type = direct'.";
    return s.str();
  }
} // namespace coulomb_adapt
