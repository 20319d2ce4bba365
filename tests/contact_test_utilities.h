// A contact scene set up and solved, for the contact tests.
#ifndef coulomb_adapt_tests_contact_test_utilities_h
#define coulomb_adapt_tests_contact_test_utilities_h

#include <deal.II/base/conditional_ostream.h>

#include <coulomb_adapt/bodies/elastic_bodies.h>
#include <coulomb_adapt/contact/contact_solver.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/scenes/scene_factory.h>

#include "test_utilities.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

namespace coulomb_adapt
{
  namespace testing
  {
    struct SolvedContactProblem
    {
      ParameterHandler               prm;
      Parameters                     parameters;
      std::unique_ptr<Scene>         scene;
      ElasticBodies                  bodies;
      std::unique_ptr<ContactSolver> solver;
      ContactSolverReport            report;
      /** The Newton log (not printed: iteration details may vary). */
      std::ostringstream log;
    };

    /** The scene's bodies set up and assembled, the solver created but
     * not run. */
    inline std::unique_ptr<SolvedContactProblem>
    solve_contact_setup(
      const std::vector<std::pair<std::string, std::string>> &settings,
      const std::string &parameter_file = "")
    {
      auto p        = std::make_unique<SolvedContactProblem>();
      p->parameters = make_parameters(p->prm, settings, parameter_file);
      p->scene      = scenes::create_scene(p->parameters, p->prm);
      p->bodies     = make_bodies(MPI_COMM_WORLD,
                              *p->scene,
                              p->parameters,
                              p->parameters.mesh.global_refinements);
      for (auto &body : p->bodies)
        {
          body->setup_system();
          body->assemble_system();
        }
      static ConditionalOStream quiet(std::cout, false);
      p->solver = std::make_unique<ContactSolver>(*p->bodies[0],
                                                  *p->bodies[1],
                                                  p->parameters.contact,
                                                  p->parameters.linear_solver,
                                                  quiet);
      return p;
    }

    /** The same, solved from the initial gap. */
    inline std::unique_ptr<SolvedContactProblem>
    solve_contact(
      const std::vector<std::pair<std::string, std::string>> &settings,
      const std::string &parameter_file = "")
    {
      auto p    = solve_contact_setup(settings, parameter_file);
      p->report = p->solver->solve();
      return p;
    }

    /** solve_contact on the example parameter file prm/@p parameter_file
     * with the gmsh mesh prm/meshes/@p mesh_file (example_file), and
     * @p settings. */
    inline std::unique_ptr<SolvedContactProblem>
    solve_example(const std::string &parameter_file,
                  const std::string &mesh_file,
                  const Settings    &settings = {})
    {
      Settings all = {
        {"Scene/Gmsh/Mesh file", example_file("meshes/" + mesh_file)}};
      all.insert(all.end(), settings.begin(), settings.end());
      return solve_contact(all, example_file(parameter_file));
    }

    /** max over the bodies of |a - b| / |a|, over the locally owned
     * entries (solution vectors have ghost entries). */
    inline double
    relative_difference(const std::array<TrilinosWrappers::MPI::Vector, 2> &a,
                        const std::array<TrilinosWrappers::MPI::Vector, 2> &b)
    {
      double worst = 0;
      for (unsigned int k = 0; k < 2; ++k)
        {
          double difference = 0, norm = 0;
          for (const auto i : a[k].locally_owned_elements())
            {
              difference += std::pow(a[k][i] - b[k][i], 2);
              norm += std::pow(a[k][i], 2);
            }
          worst =
            std::max(worst,
                     std::sqrt(Utilities::MPI::sum(difference, MPI_COMM_WORLD) /
                               Utilities::MPI::sum(norm, MPI_COMM_WORLD)));
        }
      return worst;
    }

    /** blocks with a stiff, nearly incompressible body 1 on a soft one
     * (E1/E2 = 1e3, nu = 0.499 on both), body 1 not held sideways: the
     * family of the stability sweep's hardest cases (doc/contact.md §3).
     * Further settings are appended by the caller. */
    inline std::vector<std::pair<std::string, std::string>>
    stiff_slave_blocks(const std::string &pressure,
                       const std::string &upper_subdivisions,
                       const std::string &lower_subdivisions)
    {
      const std::string b = "Scene/Blocks/";
      return {{"Scene/Name", "blocks"},
              {b + "Pressure", pressure},
              {b + "Upper body subdivisions", upper_subdivisions},
              {b + "Lower body subdivisions", lower_subdivisions},
              {b + "Hold centre line", "false"},
              {b + "Body 1/Young's modulus", "130000000"},
              {b + "Body 2/Young's modulus", "130000"},
              {b + "Body 1/Poisson's ratio", "0.499"},
              {b + "Body 2/Poisson's ratio", "0.499"}};
    }

    /** The solved problem's displacements, body 1 and body 2. */
    inline std::array<TrilinosWrappers::MPI::Vector, 2>
    displacements(const SolvedContactProblem &p)
    {
      return {{p.bodies[0]->solution(), p.bodies[1]->solution()}};
    }


    /** The largest difference of two solutions' nodal pressures and
     * tangential tractions (the same slave nodes), relative to the
     * largest pressure of @p s. */
    inline double
    relative_traction_difference(const std::vector<ContactNodeState> &s,
                                 const std::vector<ContactNodeState> &t)
    {
      double p_max = 0, d = 0;
      for (unsigned int j = 0; j < s.size(); ++j)
        {
          p_max = std::max(p_max, s[j].pressure);
          d     = std::max(
            {d,
                 std::abs(s[j].pressure - t[j].pressure),
                 std::abs(s[j].tangential_traction - t[j].tangential_traction)});
        }
      return d / p_max;
    }

    /** Two solutions of the same contact problem agree: node-wise sets,
     * pressure and tangential traction to 1e-8 of the largest pressure,
     * displacements to 1e-8 relative. Throws with @p name otherwise. */
    inline void
    assert_same_contact_solution(const std::string          &name,
                                 const SolvedContactProblem &a,
                                 const SolvedContactProblem &b)
    {
      const auto &s         = a.solver->node_states();
      const auto &t         = b.solver->node_states();
      const auto  signature = [](const std::vector<ContactNodeState> &states) {
        std::string result;
        for (const auto &n : states)
          result += to_string(n.status)[0];
        return result;
      };
      AssertThrow(signature(s) == signature(t),
                  ExcMessage(name + ": sets differ:\n" + signature(s) + "\n" +
                             signature(t)));
      const double d = relative_traction_difference(s, t);
      AssertThrow(d <= 1e-8,
                  ExcMessage(name + ": tractions differ by " +
                             std::to_string(d)));
      const double u_difference =
        relative_difference(displacements(a), displacements(b));
      AssertThrow(u_difference <= 1e-8,
                  ExcMessage(name + ": displacements differ by " +
                             std::to_string(u_difference)));
    }

    /** The converged nodal states satisfy the contact conditions to
     * @p tolerance times the largest pressure: no negative pressure and
     * every traction in the Coulomb cone at active nodes, slip nodes on the
     * cone's edge in their slip direction, sliding that way, stick nodes
     * not sliding, open nodes free. Throws with
     * @p name and the worst violation of each otherwise. */
    inline void
    assert_contact_conditions(const std::string                   &name,
                              const std::vector<ContactNodeState> &states,
                              const double                         mu,
                              const double                         tolerance)
    {
      double p_max = 0;
      for (const auto &s : states)
        p_max = std::max(p_max, s.pressure);
      double cone = 0, edge = 0, open = 0, negative = 0;
      for (const auto &s : states)
        if (s.status == ContactStatus::open)
          open = std::max(
            {open, std::abs(s.pressure), std::abs(s.tangential_traction)});
        else
          {
            negative = std::max(negative, -s.pressure);
            cone =
              std::max(cone, std::abs(s.tangential_traction) - mu * s.pressure);
            if (s.status == ContactStatus::slip)
              edge = std::max(edge,
                              std::abs(s.tangential_traction -
                                       mu * s.slip_sign * s.pressure));
          }
      AssertThrow(std::max({cone, edge, open, negative}) <= tolerance * p_max,
                  ExcMessage(name +
                             ": contact conditions violated (of the "
                             "largest pressure): cone " +
                             std::to_string(cone / p_max) + ", edge " +
                             std::to_string(edge / p_max) + ", open " +
                             std::to_string(open / p_max) +
                             ", negative pressure " +
                             std::to_string(negative / p_max)));
      // Slip nodes slide along their traction, stick nodes do not move,
      // to @p tolerance of the largest slip increment (static problems:
      // the slip itself).
      double       max_slip = 0, backward = 0, stuck = 0;
      unsigned int n_slip = 0;
      for (const auto &s : states)
        if (s.status != ContactStatus::open)
          max_slip = std::max(max_slip, std::abs(s.slip_increment));
      for (const auto &s : states)
        if (s.status == ContactStatus::slip)
          {
            ++n_slip;
            backward = std::max(backward, -s.slip_sign * s.slip_increment);
          }
        else if (s.status == ContactStatus::stick)
          stuck = std::max(stuck, std::abs(s.slip_increment));
      if (mu > 0 && n_slip > 0)
        AssertThrow(std::max(backward, stuck) <= tolerance * max_slip,
                    ExcMessage(name + ": slip against the traction " +
                               std::to_string(backward / max_slip) +
                               ", slip of stick nodes " +
                               std::to_string(stuck / max_slip) +
                               " (of the largest slip increment)"));
    }

    /** epsilon_E of every cell of both bodies, gathered on every rank in
     * CellId order (so that it does not depend on the partition). */
    inline std::vector<double>
    gathered_indicators(const std::array<const ElasticBody *, 2> &bodies,
                        const ErrorEstimate                      &e)
    {
      std::vector<std::pair<std::string, double>> local;
      for (unsigned int b = 0; b < 2; ++b)
        for (const auto &cell :
             bodies[b]->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            local.emplace_back(std::to_string(b) + cell->id().to_string(),
                               e.indicator[b](cell->active_cell_index()));
      std::vector<std::pair<std::string, double>> all;
      for (const auto &v : Utilities::MPI::all_gather(MPI_COMM_WORLD, local))
        all.insert(all.end(), v.begin(), v.end());
      std::sort(all.begin(), all.end());
      std::vector<double> values;
      for (const auto &[id, value] : all)
        values.push_back(value);
      return values;
    }

    /** The half-width of a Hertz-like contact zone centred at x = 0: the
     * least-squares fit p^2 = c0 + c1 x^2 over the nodes in contact (the
     * elliptic pressure p0 sqrt(1 - x^2 / a^2) squared is exactly this), a
     * = sqrt(-c0 / c1). Uses every contact node rather than the first open
     * one, so that it resolves a between nodes. */
    inline double
    fitted_half_width(const std::vector<ContactNodeState> &states)
    {
      double s00 = 0, s01 = 0, s11 = 0, r0 = 0, r1 = 0;
      for (const auto &s : states)
        if (s.status != ContactStatus::open)
          {
            const double X = s.position[0] * s.position[0],
                         Y = s.pressure * s.pressure;
            s00 += 1;
            s01 += X;
            s11 += X * X;
            r0 += Y;
            r1 += X * Y;
          }
      const double det = s00 * s11 - s01 * s01;
      const double c0  = (r0 * s11 - r1 * s01) / det;
      const double c1  = (s00 * r1 - s01 * r0) / det;
      return std::sqrt(-c0 / c1);
    }
  } // namespace testing
} // namespace coulomb_adapt

#endif
