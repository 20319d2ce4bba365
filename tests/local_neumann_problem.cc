// The local Neumann problems of the constitutive-relation-error estimator
// (LocalNeumannProblem, theory.md section 7.3) on their own, against exact
// polynomial solutions of elasticity without body force: u = grad phi with
// phi = Re(zeta^(n+1)) / (n+1), zeta = ((x - x_E) + i (y - y_E)) / h_E, a
// displacement of degree n with div u = 0 and Laplace u = 0, hence
// sigma = 2 mu eps(u) and div sigma = 0. Each cell of the blocks' meshes
// (P1 triangles, Q1 quadrilaterals) is loaded with the tractions sigma(u) n
// on its faces.
//  - n <= P (the local problems' degree): u is in the local space, so the
//    energy of the response, |L^-1 l|^2 (whiten()) and ||sigma^||^2 from
//    the solved coefficients (solve(), errors() against sigma_c = 0), equals
//    int sigma(u) : eps(u) to round-off (measured: at most 4e-14), and the
//    load is self-equilibrated to round-off (2.5e-14);
//  - n = P + 1: u is not in the space, and the Galerkin response has less
//    energy than u (the minimum of the complementary energy is the exact
//    one only when the space holds it).
// The stiffness is assembled from the cell's monomial moments, so this
// checks that assembly against a quadrature of the exact field.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/indicator/local_neumann_problem.h>

#include "contact_test_utilities.h"

#include <complex>
#include <iomanip>

using namespace coulomb_adapt;

namespace
{
  // grad u of u = grad phi, phi = Re(zeta^(n+1)) / (n+1): the Hessian of
  // phi, from phi'' = n zeta^(n-1) / h^2.
  Tensor<2, 2>
  displacement_gradient(const Point<2>    &x,
                        const Point<2>    &centre,
                        const double       h,
                        const unsigned int n)
  {
    const std::complex<double> zeta((x[0] - centre[0]) / h,
                                    (x[1] - centre[1]) / h);
    const std::complex<double> second =
      double(n) * std::pow(zeta, int(n) - 1) / (h * h);
    Tensor<2, 2> G;
    G[0][0] = second.real();
    G[0][1] = G[1][0] = -second.imag();
    G[1][1]           = -second.real();
    return G;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const unsigned int P = 4; // p = 1, CRE degree increase 3
  for (const std::string cell_type : {"triangle", "quadrilateral"})
    {
      const auto problem =
        testing::solve_contact_setup({{"Scene/Name", "blocks"},
                                      {"Mesh/Cell type", cell_type},
                                      {"Contact/Friction coefficient", "0"}});
      const ElasticBody  &body = *problem->bodies[1];
      const double        mu   = body.material().mu();
      LocalNeumannProblem local(body, P);
      // Quadratures exact for the energies (degree 2 (n - 1) <= 8) and the
      // face loads (degree n + P <= 9) on these straight-sided cells.
      const Quadrature<2> cell_rule =
        body.is_simplex_mesh() ? Quadrature<2>(QWitherdenVincentSimplex<2>(6)) :
                                 Quadrature<2>(QGauss<2>(6));
      FEValues<2>     fe_values(body.mapping(),
                            body.dof_handler().get_fe(),
                            cell_rule,
                            update_quadrature_points | update_JxW_values);
      const QGauss<1> face_rule(6);

      for (unsigned int n = 2; n <= P + 1; ++n)
        {
          double         worst_energy = 0, worst_solved = 0, worst_rigid = 0;
          double         least_deficit = 1;
          unsigned int   n_cells       = 0;
          Vector<double> load(local.n_coefficients()), w, coefficients;
          for (const auto &cell : body.dof_handler().active_cell_iterators())
            if (cell->is_locally_owned())
              {
                ++n_cells;
                const Point<2> centre = cell->center();
                const double   h      = cell->diameter();
                local.reinit(cell, body.solution()); // sigma_c = 0
                load = 0;
                for (const unsigned int f : cell->face_indices())
                  {
                    const Point<2> v0     = cell->face(f)->vertex(0);
                    const Point<2> v1     = cell->face(f)->vertex(1);
                    const double   length = v0.distance(v1);
                    Tensor<1, 2>   normal({(v1 - v0)[1], -(v1 - v0)[0]});
                    normal /= length;
                    if ((cell->face(f)->center() - centre) * normal < 0)
                      normal = -normal;
                    for (unsigned int q = 0; q < face_rule.size(); ++q)
                      {
                        const Point<2> x =
                          v0 + face_rule.point(q)[0] * (v1 - v0);
                        const Tensor<2, 2> G =
                          displacement_gradient(x, centre, h, n);
                        // sigma = 2 mu eps (tr eps = 0), G symmetric.
                        local.add_traction(load,
                                           x,
                                           2 * mu * G * normal,
                                           face_rule.weight(q) * length,
                                           {{true, true}});
                      }
                  }
                double exact = 0;
                fe_values.reinit(cell);
                for (const unsigned int q :
                     fe_values.quadrature_point_indices())
                  {
                    const Tensor<2, 2> G = displacement_gradient(
                      fe_values.quadrature_point(q), centre, h, n);
                    exact += 2 * mu * scalar_product(G, G) * fe_values.JxW(q);
                  }
                local.whiten(load, w);
                worst_rigid =
                  std::max(worst_rigid, local.solve(load, coefficients));
                const double energy = w * w;
                const double solved = local.errors(coefficients)[0];
                if (n <= P)
                  {
                    worst_energy =
                      std::max(worst_energy, std::abs(energy / exact - 1));
                    worst_solved =
                      std::max(worst_solved, std::abs(solved / exact - 1));
                  }
                else
                  least_deficit = std::min(least_deficit, 1 - energy / exact);
              }
          n_cells       = Utilities::MPI::sum(n_cells, MPI_COMM_WORLD);
          worst_energy  = Utilities::MPI::max(worst_energy, MPI_COMM_WORLD);
          worst_solved  = Utilities::MPI::max(worst_solved, MPI_COMM_WORLD);
          worst_rigid   = Utilities::MPI::max(worst_rigid, MPI_COMM_WORLD);
          least_deficit = -Utilities::MPI::max(-least_deficit, MPI_COMM_WORLD);

          out << cell_type << ", " << n_cells << " cells, P = " << P
              << ", u of degree " << n << ": ";
          if (n <= P)
            {
              const bool ok = worst_energy < 1e-12 && worst_solved < 1e-12 &&
                              worst_rigid < 1e-13;
              out << "energy |L^-1 l|^2 and ||sigma^||^2 equal int sigma : "
                     "eps to 1e-12, load self-equilibrated to 1e-13: "
                  << (ok ? "yes" : "NO") << std::endl;
              AssertThrow(ok,
                          ExcMessage("energy " + std::to_string(worst_energy) +
                                     ", solved " +
                                     std::to_string(worst_solved) + ", rigid " +
                                     std::to_string(worst_rigid)));
            }
          else
            {
              const bool ok = least_deficit > 1e-4;
              out << "response's energy below the exact one on every cell "
                     "(by more than 1e-4 relative): "
                  << (ok ? "yes" : "NO") << ", least deficit "
                  << std::setprecision(2) << least_deficit << std::endl;
              AssertThrow(ok,
                          ExcMessage("least deficit " +
                                     std::to_string(least_deficit)));
            }
        }
    }
}
