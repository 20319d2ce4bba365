// EliminatedOperator (contact/eliminated_operator.h) computes the reduced
// system of the eliminated contact Newton step row by row,
//
//   A = Z~^T K Z,   b = Z~^T (f - K u_g),   u = Z u~ + u_g,
//
// without forming Z, Z~ or K Z. Here the same three products are formed
// explicitly as dense matrices and compared entry by entry: the largest
// difference relative to the largest entry must be round-off (1e-13).
//
// The contact case is blocks on quadrilaterals (mu = 0.3, 4 x 1 and 6 x 2
// coarse cells refined twice: a few hundred DoFs, the contact face split
// between the ranks of a 2-rank run), its mortar interface (D, M, normals)
// as the solver has it, and the slave nodes put into the three kinds of rows
// the eliminated system builds (EliminatedContactSystem::assemble): stick (both
// components eliminated, Z~ = Z), slip in either direction (one component
// eliminated, Z~ along the traction n + mu s t, not n: Z~ differs from Z) and
// open (not eliminated); one master DoF is treated as a DoF with Dirichlet data
// (Z~ = 0 there, its value in u_g). Eliminated rows of A must hold K's diagonal
// entry only, b must be zero there. 1 and 2 ranks: on 2 the eliminated rows and
// their K Z rows are gathered from the other rank.
//
// The contact solver does not store A: ReducedMatrix keeps only its rows
// near the interface and reads the others from K^1, K^2. Its rows must be
// the stored A's entry for entry, and its product A u~ the stored A's.

#include <deal.II/base/mpi.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/eliminated_operator.h>
#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/contact/reduced_matrix.h>
#include <coulomb_adapt/scenes/scene_factory.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <vector>

using namespace coulomb_adapt;

namespace
{
  // Row-major dense n x n matrix.
  struct Dense
  {
    explicit Dense(const std::size_t n)
      : n(n)
      , a(n * n, 0.)
    {}
    double &
    operator()(const std::size_t i, const std::size_t j)
    {
      return a[i * n + j];
    }
    double
    operator()(const std::size_t i, const std::size_t j) const
    {
      return a[i * n + j];
    }
    std::size_t         n;
    std::vector<double> a;
  };

  Dense
  product(const Dense &X, const Dense &Y)
  {
    Dense XY(X.n);
    for (std::size_t i = 0; i < X.n; ++i)
      for (std::size_t k = 0; k < X.n; ++k)
        if (const double x = X(i, k); x != 0)
          for (std::size_t j = 0; j < X.n; ++j)
            XY(i, j) += x * Y(k, j);
    return XY;
  }

  Dense
  transpose(const Dense &X)
  {
    Dense T(X.n);
    for (std::size_t i = 0; i < X.n; ++i)
      for (std::size_t j = 0; j < X.n; ++j)
        T(j, i) = X(i, j);
    return T;
  }

  // The stick and slip rows as EliminatedContactSystem writes them (the
  // dual basis makes D diagonal: u^1_j = (g n + s t)/D + sum_l M_jl/D u^2_l
  // at a stick node; at a slip node the normal condition eliminates one
  // component, the test space is orthogonal to w = n + mu s t).
  struct Rows
  {
    EliminatedRows rows;
    unsigned int   n_stick = 0, n_slip = 0, n_open = 0;
  };

  Rows
  contact_rows(const MortarInterface        &mortar,
               const types::global_dof_index offset,
               const double                  mu)
  {
    Rows        result;
    const auto &nodes                 = mortar.slave_nodes();
    const auto &D                     = mortar.slave_weights();
    const auto &M                     = mortar.master_coupling();
    const auto &master_nodes          = mortar.master_nodes();
    bool        dirichlet_master_done = false;
    for (unsigned int j = 0; j < nodes.size(); ++j)
      {
        if (!mortar.is_covered(j) || j % 5 == 4)
          {
            ++result.n_open;
            continue;
          }
        const Tensor<1, 2> &n = nodes[j].normal;
        const Tensor<1, 2> &t = nodes[j].tangent;
        // A gap and a slip that differ from node to node, for u_g.
        const double g = 1e-3 * (1 + 0.1 * j), s = 2e-4 * (j % 3);
        if (j % 3 == 0)
          {
            ++result.n_stick;
            for (unsigned int c = 0; c < 2; ++c)
              {
                EliminatedRow &row = result.rows[nodes[j].dofs[c]];
                for (const auto &[l, m] : M[j])
                  {
                    const double z                                = m / D[j];
                    row.entries[offset + master_nodes[l].dofs[c]] = {{z, z}};
                  }
                row.shift = (g * n[c] + s * t[c]) / D[j];
              }
            continue;
          }
        ++result.n_slip;
        const int          sign = j % 3 == 1 ? 1 : -1;
        const Tensor<1, 2> w    = n + mu * sign * t;
        const unsigned int c    = std::abs(n[0]) >= std::abs(n[1]) ? 0 : 1;
        const unsigned int o    = 1 - c;
        EliminatedRow     &row  = result.rows[nodes[j].dofs[c]];
        row.entries[nodes[j].dofs[o]] = {{-n[o] / n[c], -w[o] / w[c]}};
        for (const auto &[l, m] : M[j])
          for (unsigned int d = 0; d < 2; ++d)
            {
              const double           z = m / D[j];
              std::array<double, 2> &entry =
                row.entries[offset + master_nodes[l].dofs[d]];
              entry = {{z * n[d] / n[c], z * w[d] / w[c]}};
              // One master DoF with Dirichlet data: no test function there,
              // its value (here 1e-3 mm) goes into the shift.
              if (!dirichlet_master_done)
                {
                  row.shift += entry[0] * 1e-3;
                  entry[1]              = 0;
                  dirichlet_master_done = true;
                }
            }
        row.shift += g / (D[j] * n[c]);
      }
    return result;
  }

  void
  add_owned_rows(const TrilinosWrappers::SparseMatrix &K,
                 const IndexSet                       &owned,
                 const types::global_dof_index         offset,
                 Dense                                &dense)
  {
    for (const auto i : owned)
      for_each_entry(K,
                     i,
                     [&](const types::global_dof_index j, const double K_ij) {
                       dense(offset + i, offset + j) = K_ij;
                     });
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out  = testing::root_output();
  const MPI_Comm                   comm = MPI_COMM_WORLD;

  ParameterHandler prm;
  const Parameters parameters =
    testing::make_parameters(prm,
                             {{"Scene/Name", "blocks"},
                              {"Mesh/Cell type", "quadrilateral"},
                              {"Scene/Blocks/Upper body subdivisions", "4, 1"},
                              {"Scene/Blocks/Lower body subdivisions", "6, 2"},
                              {"Contact/Friction coefficient", "0.3"}});
  const auto scene  = scenes::create_scene(parameters, prm);
  auto       bodies = make_bodies(comm, *scene, parameters, 2);
  for (auto &body : bodies)
    {
      body->setup_system();
      body->assemble_system();
    }
  const ElasticBody &slave  = *bodies[0];
  const ElasticBody &master = *bodies[1];
  MortarInterface    mortar;
  mortar.reinit(slave, master);

  const types::global_dof_index offset = slave.dof_handler().n_dofs();
  const types::global_dof_index n      = offset + master.dof_handler().n_dofs();
  IndexSet                      owned(n);
  owned.add_indices(slave.locally_owned_dof_set());
  owned.add_indices(master.locally_owned_dof_set(), offset);
  owned.compress();

  const double   placeholder = 1e-100;
  const Rows     all         = contact_rows(mortar, offset, 0.3);
  EliminatedRows owned_rows;
  for (const auto &[k, row] : all.rows)
    if (owned.is_element(k))
      owned_rows[k] = row;

  const EliminatedOperator       operator_(slave.system_matrix(),
                                     master.system_matrix(),
                                     slave.system_rhs(),
                                     master.system_rhs(),
                                     offset,
                                     owned,
                                     comm,
                                     owned_rows,
                                     placeholder);
  TrilinosWrappers::SparseMatrix A;
  TrilinosWrappers::MPI::Vector  b;
  operator_.reduced_matrix(A);
  operator_.reduced_rhs(b);

  // K, f, Z, Z~ and u_g as dense arrays on every rank.
  Dense K(n);
  add_owned_rows(slave.system_matrix(), slave.locally_owned_dof_set(), 0, K);
  add_owned_rows(master.system_matrix(),
                 master.locally_owned_dof_set(),
                 offset,
                 K);
  Utilities::MPI::sum(K.a, comm, K.a);
  std::vector<double> f(n, 0.);
  for (const auto i : slave.locally_owned_dof_set())
    f[i] = slave.system_rhs()(i);
  for (const auto i : master.locally_owned_dof_set())
    f[offset + i] = master.system_rhs()(i);
  Utilities::MPI::sum(f, comm, f);

  Dense               Z(n), Zt(n);
  std::vector<double> u_g(n, 0.);
  for (std::size_t i = 0; i < n; ++i)
    if (all.rows.count(i) == 0)
      Z(i, i) = Zt(i, i) = 1;
  for (const auto &[k, row] : all.rows)
    {
      Z(k, k) = placeholder;
      for (const auto &[column, z] : row.entries)
        {
          Z(k, column)  = z[0];
          Zt(k, column) = z[1];
        }
      u_g[k] = row.shift;
    }

  const Dense         ZtT      = transpose(Zt);
  const Dense         A_ref    = product(ZtT, product(K, Z));
  std::vector<double> residual = f;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      residual[i] -= K(i, j) * u_g[j];
  std::vector<double> b_ref(n, 0.);
  for (std::size_t i = 0; i < n; ++i)
    if (all.rows.count(i) == 0)
      for (std::size_t r = 0; r < n; ++r)
        b_ref[i] += ZtT(i, r) * residual[r];

  // The eliminated rows are decoupled: K's diagonal entry, zero in b.
  double       A_scale = 0, A_difference = 0, b_scale = 0, b_difference = 0;
  unsigned int asymmetric = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      {
        A_scale = std::max(A_scale, std::abs(A_ref(i, j)));
        if (all.rows.count(i) == 0 && all.rows.count(j) == 0)
          asymmetric += (std::abs(A_ref(i, j) - A_ref(j, i)) >
                         1e-8 * std::abs(A_ref(i, j)));
      }
  for (std::size_t i = 0; i < n; ++i)
    b_scale = std::max(b_scale, std::abs(b_ref[i]));
  for (const auto i : owned)
    {
      const bool          eliminated = all.rows.count(i) > 0;
      std::vector<double> row(n, 0.);
      for_each_entry(A,
                     i,
                     [&](const types::global_dof_index j, const double A_ij) {
                       row[j] = A_ij;
                     });
      for (std::size_t j = 0; j < n; ++j)
        {
          const double expected =
            eliminated ? (j == i ? K(i, i) : 0.) : A_ref(i, j);
          A_difference = std::max(A_difference, std::abs(row[j] - expected));
        }
      b_difference =
        std::max(b_difference, std::abs(b(i) - (eliminated ? 0. : b_ref[i])));
    }
  A_difference = Utilities::MPI::max(A_difference, comm);
  b_difference = Utilities::MPI::max(b_difference, comm);

  // u = Z u~ + u_g for a u~ with every entry nonzero.
  TrilinosWrappers::MPI::Vector u_reduced(owned, comm), u;
  std::vector<double>           u_tilde(n);
  for (std::size_t i = 0; i < n; ++i)
    u_tilde[i] = 1e-3 * std::sin(0.37 * i + 0.1);
  for (const auto i : owned)
    u_reduced(i) = u_tilde[i];
  u_reduced.compress(VectorOperation::insert);
  EliminatedOperator::expand(owned_rows, placeholder, u_reduced, u);
  double u_scale = 0, u_difference = 0;
  for (std::size_t i = 0; i < n; ++i)
    {
      double expected = u_g[i];
      for (std::size_t j = 0; j < n; ++j)
        expected += Z(i, j) * u_tilde[j];
      u_scale = std::max(u_scale, std::abs(expected));
      if (owned.is_element(i))
        u_difference = std::max(u_difference, std::abs(u(i) - expected));
    }
  u_difference = Utilities::MPI::max(u_difference, comm);

  // The same A without a copy of K (ReducedMatrix): its rows, with their
  // global columns, must be the stored matrix's entry for entry, and its
  // product A u~ the stored matrix's (to round-off on 2 ranks, where the
  // column order of a row, and so the order of the sums, is the matrix's
  // own).
  const std::shared_ptr<ReducedMatrix> A_rows = operator_.reduced_operator();
  unsigned int                         n_rows_differing = 0;
  {
    std::vector<double> values(A_rows->MaxNumEntries());
    std::vector<int>    columns(A_rows->MaxNumEntries());
    for (const auto i : owned)
      {
        std::vector<std::pair<types::global_dof_index, double>> stored, rows;
        for_each_entry(A,
                       i,
                       [&](const types::global_dof_index j, const double a) {
                         stored.emplace_back(j, a);
                       });
        int n_entries = 0;
        AssertThrow(A_rows->ExtractMyRowCopy(A_rows->RowMatrixRowMap().LID(
                                               static_cast<int>(i)),
                                             values.size(),
                                             n_entries,
                                             values.data(),
                                             columns.data()) == 0,
                    ExcInternalError());
        for (int e = 0; e < n_entries; ++e)
          rows.emplace_back(A_rows->RowMatrixColMap().GID(columns[e]),
                            values[e]);
        std::sort(stored.begin(), stored.end());
        std::sort(rows.begin(), rows.end());
        n_rows_differing += (stored != rows);
      }
  }
  n_rows_differing = Utilities::MPI::sum(n_rows_differing, comm);
  const unsigned int n_rows_stored =
    Utilities::MPI::sum(static_cast<unsigned int>(A_rows->n_explicit_rows()),
                        comm);
  TrilinosWrappers::MPI::Vector Au(owned, comm), Au_rows(owned, comm);
  A.vmult(Au, u_reduced);
  AssertThrow(A_rows->Multiply(false,
                               u_reduced.trilinos_vector(),
                               Au_rows.trilinos_vector()) == 0,
              ExcInternalError());
  const double Au_scale = Au.linfty_norm();
  Au_rows -= Au;
  const double Au_difference = Au_rows.linfty_norm();

  unsigned int n_eliminated = all.rows.size();
  out << "blocks Q1, 2 refinements: " << n << " DoFs, "
      << mortar.slave_nodes().size() << " slave nodes: " << all.n_stick
      << " stick, " << all.n_slip << " slip, " << all.n_open << " open; "
      << n_eliminated << " eliminated components" << std::endl;
  // On 2 ranks both must own eliminated rows, so that rows of A and b
  // need the other rank's eliminated rows.
  const unsigned int n_ranks_with_rows =
    Utilities::MPI::sum(owned_rows.empty() ? 0u : 1u, comm);
  AssertThrow(n_ranks_with_rows == Utilities::MPI::n_mpi_processes(comm),
              ExcMessage("a rank owns no eliminated row"));
  out << "ranks owning eliminated rows: " << n_ranks_with_rows << std::endl;
  out << "A = Z~^T K Z: " << asymmetric
      << " entries differ from their transpose (slip rows)" << std::endl;
  out << std::scientific << std::setprecision(2);
  const double tolerance = 1e-13;
  const auto   report =
    [&](const std::string &name, const double scale, const double difference) {
      const double relative = difference / scale;
      out << name << ": largest entry " << scale
          << ", largest difference / largest entry " << relative
          << " (below 1e-13: " << (relative <= tolerance ? "yes" : "no") << ")"
          << std::endl;
      AssertThrow(scale > 0 && relative <= tolerance,
                  ExcMessage(name + " differs from the dense product"));
    };
  report("A", A_scale, A_difference);
  report("b", b_scale, b_difference);
  report("u", u_scale, u_difference);
  out << "A from K's rows: " << n_rows_stored << " of " << n << " rows stored, "
      << n_rows_differing << " rows differ from the matrix's" << std::endl;
  AssertThrow(n_rows_differing == 0,
              ExcMessage("a row of ReducedMatrix differs from A's"));
  report("A u~ from K's rows", Au_scale, Au_difference);
}
