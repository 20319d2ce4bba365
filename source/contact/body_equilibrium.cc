#include <deal.II/base/mpi.h>
#include <deal.II/base/symmetric_tensor.h>

#include <coulomb_adapt/contact/body_equilibrium.h>
#include <coulomb_adapt/solvers/matrix_rows.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace coulomb_adapt
{
  namespace
  {
    std::vector<double>
    summed(const std::vector<double> &values, const MPI_Comm comm)
    {
      std::vector<double> result(values.size());
      Utilities::MPI::sum(make_array_view(values),
                          comm,
                          make_array_view(result));
      return result;
    }


    // The rigid modes at point x: x- and y-translation and the rotation
    // about c divided by L (a force-like mode: the moment over an arm L).
    std::array<Tensor<1, 2>, 3>
    rigid_modes_at(const Point<2> &x, const Point<2> &c, const double L)
    {
      return {{Tensor<1, 2>({1., 0.}),
               Tensor<1, 2>({0., 1.}),
               Tensor<1, 2>({-(x[1] - c[1]) / L, (x[0] - c[0]) / L})}};
    }



    // The mean position of the body's vertices and the largest distance of
    // a vertex from it, over all ranks.
    std::pair<Point<2>, double>
    centre_and_extent(const ElasticBody &body)
    {
      const MPI_Comm      comm = body.triangulation().get_communicator();
      std::vector<double> sums(3, 0.);
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto v : cell->vertex_indices())
            {
              sums[0] += cell->vertex(v)[0];
              sums[1] += cell->vertex(v)[1];
              sums[2] += 1;
            }
      sums = summed(sums, comm);
      const Point<2> centre(sums[0] / std::max(sums[2], 1.),
                            sums[1] / std::max(sums[2], 1.));
      double         extent = 0;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto v : cell->vertex_indices())
            extent = std::max(extent, centre.distance(cell->vertex(v)));
      extent = Utilities::MPI::max(extent, comm);
      return {centre, extent > 0 ? extent : 1.};
    }



    // Orthonormal basis (in the scaled coordinates of rigid_modes_at) of
    // the rigid motions the body's Dirichlet data leave free: the null
    // space of their Gram matrix.
    std::vector<Tensor<1, 3>>
    free_modes(const ElasticBody &body, const Point<2> &centre, const double L)
    {
      const FullMatrix<double> gram     = body.support_gram(centre);
      const double             scale[3] = {1., 1., 1. / L};
      SymmetricTensor<2, 3>    g;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = a; b < 3; ++b)
          g[a][b] = scale[a] * gram(a, b) * scale[b];
      const double              trace_g = trace(g);
      std::vector<Tensor<1, 3>> modes;
      if (trace_g == 0)
        {
          for (unsigned int a = 0; a < 3; ++a)
            {
              Tensor<1, 3> e;
              e[a] = 1;
              modes.push_back(e);
            }
          return modes;
        }
      for (const auto &[value, vector] : eigenvectors(g))
        if (value <= 1e-10 * trace_g)
          modes.push_back(vector);
      return modes;
    }
  } // namespace



  // Balanced to round-off is a statement only while the round-off is below the
  // forces that balance: a body that nothing holds shows an imbalance of the
  // size of its load, and a bound above that size would accept it. Where the
  // bound lies follows from the solve. In a regular system the terms of K u
  // are at most the condition number times the forces, and the bound is the
  // number of terms times eps times that: far below the forces unless the
  // condition number approaches 1 / (terms eps), about 1e14, where the contact
  // pressures, differences of the same nodal forces, have lost their digits
  // too (why body 1 may be at most 1e8 times stiffer than body 2). In a
  // singular system (the sets do not hold the body) the direct solver's pivot
  // along the free motion is itself round-off, eps times the entries of K, so
  // the displacement along it is the load over eps |K|, the terms of K u are
  // the forces over eps, and the bound is the number of terms times the forces
  // or more. The comparison with the forces needs no threshold of its own.
  // A mode along which nothing acts (no load, no contact force, no stress)
  // balances exactly.
  bool
  BodyEquilibrium::balanced() const
  {
    return imbalance <= round_off &&
           (round_off < force_scale || round_off == 0);
  }



  namespace
  {
    // What the body's own equations give along the rigid modes z_m
    // (translations, rotation about the centre over L): sums[m] = z_m^T f,
    // sums[3 + m] = sum |z_m,i| (|f_i| + sum_j |K_ij u_j|), sums[6 + m] =
    // max |z_m,i|, sums[9] = |f|_1, sums[10] = the number of rows, over the
    // unconstrained rows of all ranks, and the longest row.
    struct ResidualSums
    {
      std::vector<double> sums;
      unsigned int        max_row_length = 0;
    };

    ResidualSums
    residual_sums(const ElasticBody &body,
                  const Point<2>    &centre,
                  const double       L)
    {
      // (The rows of constrained DoFs are not equations of the body.)
      const auto &K     = body.system_matrix();
      const auto &f     = body.system_rhs();
      const auto &u     = body.solution();
      const auto &owned = body.locally_owned_dof_set();
      const auto &modes = body.rigid_body_modes();
      // [load_m (3), magnitude_m (3), max |z_m| (3), |f|_1, rows]
      std::vector<double> sums(11, 0.);
      unsigned int        max_row_length = 0;
      double              z_max[3]       = {0, 0, 0};
      for (unsigned int k = 0; k < owned.n_elements(); ++k)
        {
          const auto i = owned.nth_index_in_set(k);
          if (body.constraints().is_constrained(i))
            continue;
          double       magnitude = std::abs(f(i));
          unsigned int length    = 0;
          for_each_entry(K, i, [&](const auto column, const double value) {
            magnitude += std::abs(value * u(column));
            ++length;
          });
          max_row_length = std::max(max_row_length, length);
          // Rotation about the centre, over L: the rotation about the origin
          // less the translation of the centre.
          const double z[3] = {modes[0][k],
                               modes[1][k],
                               (modes[2][k] + centre[1] * modes[0][k] -
                                centre[0] * modes[1][k]) /
                                 L};
          for (unsigned int m = 0; m < 3; ++m)
            {
              sums[m] += z[m] * f(i);
              sums[3 + m] += std::abs(z[m]) * magnitude;
              z_max[m] = std::max(z_max[m], std::abs(z[m]));
            }
          sums[9] += std::abs(f(i));
          sums[10] += 1;
        }
      const MPI_Comm comm = body.triangulation().get_communicator();
      ResidualSums   result;
      result.sums = summed(sums, comm);
      for (unsigned int m = 0; m < 3; ++m)
        result.sums[6 + m] = Utilities::MPI::max(z_max[m], comm);
      result.max_row_length = Utilities::MPI::max(max_row_length, comm);
      return result;
    }



    // The contact forces' resultants along the rigid modes, and the sums
    // of their magnitudes, from the multipliers every rank holds.
    std::pair<Tensor<1, 3>, Tensor<1, 3>>
    contact_resultants(const bool                           slave,
                       const MortarInterface               &mortar,
                       const std::vector<ContactNodeState> &states,
                       const Point<2>                      &centre,
                       const double                         L)
    {
      Tensor<1, 3> contact, contact_magnitude;
      const auto add_force = [&](const Point<2> &x, const Tensor<1, 2> &force) {
        const auto z = rigid_modes_at(x, centre, L);
        for (unsigned int m = 0; m < 3; ++m)
          {
            contact[m] += z[m] * force;
            contact_magnitude[m] += std::abs(z[m] * force);
          }
      };
      const auto &D = mortar.slave_weights();
      if (slave)
        for (unsigned int j = 0; j < states.size(); ++j)
          add_force(states[j].position,
                    -D[j] *
                      (states[j].pressure * states[j].normal +
                       states[j].tangential_traction * states[j].tangent));
      else
        {
          const auto               &M       = mortar.master_coupling();
          const auto               &masters = mortar.master_nodes();
          std::vector<Tensor<1, 2>> force(masters.size());
          for (unsigned int j = 0; j < states.size(); ++j)
            for (const auto &[l, m] : M[j])
              force[l] +=
                m * (states[j].pressure * states[j].normal +
                     states[j].tangential_traction * states[j].tangent);
          for (unsigned int l = 0; l < masters.size(); ++l)
            add_force(masters[l].position, force[l]);
        }

      return {contact, contact_magnitude};
    }
  } // namespace



  BodyEquilibrium
  body_equilibrium(const ElasticBody                   &body,
                   const bool                           slave,
                   const MortarInterface               &mortar,
                   const std::vector<ContactNodeState> &states,
                   const double                         linear_tolerance)
  {
    BodyEquilibrium result;
    const auto [centre, L] = centre_and_extent(body);
    result.centre          = centre;
    const auto free        = free_modes(body, centre, L);
    result.n_free_modes    = free.size();
    if (free.empty())
      return result;
    const auto [sums, max_row_length] = residual_sums(body, centre, L);
    const auto [contact, contact_magnitude] =
      contact_resultants(slave, mortar, states, centre, L);

    const double eps = std::numeric_limits<double>::epsilon();
    // Each row's terms carry (row length + 1) eps of their magnitudes;
    // the sum over the rows adds about sqrt(number of terms) eps (the
    // worst case, linear in the number, would exceed the forces on fine
    // meshes: 2.8e-6 of them on the hertz mesh of contact_nested_iteration,
    // whose imbalance is 8e-11 N/mm for 1e3 N/mm).
    const double n_terms =
      max_row_length + 2 +
      std::sqrt(sums[10] + states.size() + mortar.master_nodes().size());
    for (const auto &v : free)
      {
        double sum = 0, magnitude = 0, z_size = 0, scale = 0;
        for (unsigned int m = 0; m < 3; ++m)
          {
            sum += v[m] * (sums[m] + contact[m]);
            magnitude += std::abs(v[m]) * (sums[3 + m] + contact_magnitude[m]);
            z_size += std::abs(v[m]) * sums[6 + m];
            scale +=
              std::abs(v[m]) * (std::abs(sums[m]) + contact_magnitude[m]);
          }
        // A Krylov solve leaves |r|_2 <= tol |b|_2, and |z^T r| <= |z|_2
        // |r|_2 <= sqrt(n) max |z_i| tol |f|_1 (norms that do not
        // overflow before the loads do).
        const double bound =
          n_terms * eps * magnitude +
          (linear_tolerance > 0 ?
             10 * linear_tolerance * std::sqrt(sums[10]) * z_size * sums[9] :
             0.);
        result.imbalance   = std::max(result.imbalance, std::abs(sum));
        result.round_off   = std::max(result.round_off, bound);
        result.force_scale = std::max(result.force_scale, scale);
      }

    // What the log and the message show: the resultants along the free
    // modes (a held direction shows 0).
    Tensor<1, 3> load, contact_free, imbalance;
    for (const auto &v : free)
      {
        double l = 0, c = 0;
        for (unsigned int m = 0; m < 3; ++m)
          {
            l += v[m] * sums[m];
            c += v[m] * contact[m];
          }
        load += l * v;
        contact_free += c * v;
      }
    imbalance             = load + contact_free;
    result.load_force     = Tensor<1, 2>({load[0], load[1]});
    result.contact_force  = Tensor<1, 2>({contact_free[0], contact_free[1]});
    result.load_moment    = load[2] * L;
    result.contact_moment = contact_free[2] * L;
    result.tips =
      std::abs(imbalance[2]) > std::hypot(imbalance[0], imbalance[1]);
    return result;
  }



  std::string
  equilibrium_message(const std::string &body_label, const BodyEquilibrium &e)
  {
    std::ostringstream s;
    s << std::setprecision(3);
    s << body_label << " is not in equilibrium: its applied load ("
      << e.load_force[0] << ", " << e.load_force[1] << ") N/mm with moment "
      << e.load_moment << " N about (" << e.centre[0] << ", " << e.centre[1]
      << "), the contact force on it (" << e.contact_force[0] << ", "
      << e.contact_force[1] << ") N/mm with moment " << e.contact_moment
      << " N: out of balance by " << e.imbalance
      << " N/mm, where round-off allows " << e.round_off << " N/mm";
    if (e.round_off >= e.force_scale && e.round_off > 0)
      s << " (a round-off as large as the forces themselves: the system "
           "is singular, the contact sets do not hold the body)";
    s << ". The contact does not hold the body: it slides or tips (the "
      << "imbalance is mostly a " << (e.tips ? "moment" : "force")
      << "): no static equilibrium exists for this load and geometry (a "
         "tangential load above mu times the normal load, a load outside "
         "the zone the contact can support, contact curves that do not "
         "face the load), or the active set iteration went astray (try "
         "another 'Contact/Complementarity scale').";
    return s.str();
  }
} // namespace coulomb_adapt
