// The exact error's reference solution on adapted meshes (theory.md
// section 8): the judged meshes themselves refined R = 2 times.
//  - manufactured elasticity (exact solution known) on meshes adapted by
//    the program's own adaptation (quadrilaterals with hanging nodes,
//    remeshed triangles): the exact error against the reference falls
//    short of the true one only by the reference's own error, and the
//    error the reference states for itself (the change from R - 1 to R) is
//    at least its true error;
//  - the energy check e^2 = 2 (U_ref - U_h): to round-off on the contact
//    patch test (both solutions exact), and on blocks with frictionless
//    contact (`Hold centre line`) on adapted meshes to the contact work
//    the identity leaves out.
// The identity e^2 = d^2 + e_R^2 of nested spaces holds to 1e-4 on the
// triangles (to 1e-3 with hanging nodes). Extrapolated over the three
// levels (judged, R - 1, R; a geometric decay per level), the exact error
// is recovered to 2e-3 there.
// 1 and 2 ranks: the same numbers.

#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/indicator/exact_error.h>

#include "contact_test_utilities.h"

#include <cmath>
#include <iomanip>

using namespace coulomb_adapt;

namespace
{
  struct Problem
  {
    ParameterHandler                            prm;
    Parameters                                  parameters;
    std::unique_ptr<Scene>                      scene;
    std::array<std::unique_ptr<ElasticBody>, 2> bodies;
    std::unique_ptr<ContactSolver>              solver;

    std::array<const ElasticBody *, 2>
    pointers() const
    {
      return {{bodies[0].get(), bodies[1].get()}};
    }

    std::array<const TrilinosWrappers::MPI::Vector *, 2>
    solutions() const
    {
      return {{&bodies[0]->solution(), &bodies[1]->solution()}};
    }

    bool
    has_contact() const
    {
      return bodies[0]->description().contact_boundary_id !=
             numbers::invalid_boundary_id;
    }

    void
    solve()
    {
      for (auto &body : bodies)
        {
          body->setup_system();
          body->assemble_system();
        }
      if (!has_contact())
        {
          for (auto &body : bodies)
            body->solve(parameters.linear_solver);
          return;
        }
      static ConditionalOStream quiet(std::cout, false);
      solver = std::make_unique<ContactSolver>(*bodies[0],
                                               *bodies[1],
                                               parameters.contact,
                                               parameters.linear_solver,
                                               quiet);
      solver->solve();
    }

    // One cycle of the program's adaptation, driven by its own indicator.
    void
    adapt()
    {
      ErrorEstimate estimate =
        estimate_error(pointers(),
                       solver.get(),
                       parameters.contact.friction_coefficient,
                       StressRecoveryMethod::l2_projection,
                       parameters.linear_solver);
      const std::vector<ContactNodeState> states =
        solver ? solver->node_states() : std::vector<ContactNodeState>();
      solver.reset();
      adapt_meshes({{bodies[0].get(), bodies[1].get()}},
                   estimate,
                   states,
                   parameters.adaptation,
                   parameters.finite_elements.degree,
                   parameters.adaptation.target_error,
                   false);
      solve();
    }
  };

  std::unique_ptr<Problem>
  solved_problem(
    const std::vector<std::pair<std::string, std::string>> &settings,
    const unsigned int                                      n_adaptations)
  {
    auto p        = std::make_unique<Problem>();
    p->parameters = testing::make_parameters(p->prm, settings);
    p->scene      = scenes::create_scene(p->parameters, p->prm);
    for (unsigned int b = 0; b < 2; ++b)
      p->bodies[b] =
        std::make_unique<ElasticBody>(MPI_COMM_WORLD,
                                      *p->scene,
                                      b,
                                      p->parameters.mesh.cell_type,
                                      p->parameters.mesh.global_refinements,
                                      p->parameters.finite_elements);
    p->solve();
    for (unsigned int i = 0; i < n_adaptations; ++i)
      p->adapt();
    return p;
  }

  // Cells of both bodies, and the ratio of the largest to the smallest
  // cell diameter: the meshes are not uniform.
  std::string
  describe_mesh(const Problem &p)
  {
    types::global_cell_index n_cells  = 0;
    double                   smallest = 1e300, largest = 0;
    for (const auto &body : p.bodies)
      {
        n_cells += body->triangulation().n_global_active_cells();
        for (const auto &cell : body->triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              smallest = std::min(smallest, cell->diameter());
              largest  = std::max(largest, cell->diameter());
            }
      }
    smallest = Utilities::MPI::min(smallest, MPI_COMM_WORLD);
    largest  = Utilities::MPI::max(largest, MPI_COMM_WORLD);
    std::ostringstream s;
    s << n_cells << " cells, largest/smallest diameter " << std::setprecision(3)
      << largest / smallest;
    return s.str();
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  out << std::scientific << std::setprecision(3);

  out << "Manufactured solution on adapted meshes, reference R = 2"
      << std::endl;
  for (const auto &[cell_type, strategy] :
       std::vector<std::pair<std::string, std::string>>{
         {"quadrilateral", "refine"}, {"triangle", "remesh"}})
    {
      const auto p = solved_problem({{"Scene/Name", "manufactured"},
                                     {"Mesh/Cell type", cell_type},
                                     {"Mesh/Global refinements", "2"},
                                     {"Adaptation/Strategy", strategy},
                                     {"Adaptation/Target error", "3"}},
                                    1);
      const ExactSolutionStress exact(p->pointers());
      const StressDifference    e =
        compare_stresses(p->pointers(), p->solutions(), exact, 1);
      const ReferenceSolutionStress reference(*p->scene,
                                              p->parameters,
                                              p->pointers(),
                                              2);
      const StressDifference        d =
        compare_stresses(p->pointers(), p->solutions(), reference, 4);
      // The reference's true error, normalised like its stated one.
      const std::array<const ElasticBody *, 2> reference_bodies = {
        {&reference.body(0), &reference.body(1)}};
      const StressDifference e_reference =
        compare_stresses(reference_bodies,
                         {{&reference.body(0).solution(),
                           &reference.body(1).solution()}},
                         exact,
                         1);
      const double epsilon_true =
        std::sqrt(e.difference_squared / e.sum_squared);
      const double epsilon_reference =
        std::sqrt(d.difference_squared / d.sum_squared);
      const double reference_true =
        std::sqrt(e_reference.difference_squared / e_reference.sum_squared);
      out << "  " << cell_type << " (" << describe_mesh(*p)
          << "): epsilon exact " << epsilon_true << ", against the reference "
          << epsilon_reference << "; reference error: true " << reference_true
          << ", stated " << reference.own_error() << " (from the energies "
          << reference.own_error_from_energy() << ")" << std::endl;
      // Nested spaces: e^2 = |sigma_R - sigma_h|^2 + |sigma - sigma_R|^2
      // up to the interpolated Dirichlet data (not nested).
      const double pythagoras =
        std::abs(e.difference_squared - d.difference_squared -
                 e_reference.difference_squared) /
        e.difference_squared;
      out << "    |e^2 - d^2 - e_R^2| / e^2 = " << pythagoras << std::endl;
      // Triangles: 8.4e-6 since the reference stress is read in the cell
      // that holds each point (before, deal.II's RemotePointEvaluation
      // took a neighbour for 1 in 16 points: 5.8e-4); quadrilaterals with
      // hanging nodes 2.9e-4.
      AssertThrow(pythagoras < (cell_type == "triangle" ? 1e-4 : 1e-3),
                  ExcMessage("Pythagoras fails"));
      AssertThrow(epsilon_reference <= epsilon_true &&
                    epsilon_reference >=
                      std::sqrt(std::pow(epsilon_true, 2) -
                                std::pow(reference.own_error(), 2)),
                  ExcMessage("the stated reference error does not explain "
                             "the deficit"));
      AssertThrow(reference.own_error() >= reference_true,
                  ExcMessage("the stated reference error is below the true"));
      // The three levels (judged, R - 1, R) extrapolated: the exact error
      // recovered to a small fraction of the deficit above.
      const double extrapolated =
        extrapolated_exact_error(epsilon_reference, reference.own_error(), 2);
      const double extrapolation_error =
        std::abs(extrapolated - epsilon_true) / epsilon_true;
      out << "    extrapolated exact error " << extrapolated
          << ": |extrapolated - exact| / exact = " << extrapolation_error
          << " (against the reference alone "
          << (epsilon_true - epsilon_reference) / epsilon_true << ")"
          << std::endl;
      AssertThrow(extrapolation_error < 2e-3,
                  ExcMessage("the extrapolated exact error is off"));
    }

  out << "Energy check e^2 = 2 (U_ref - U_h)" << std::endl;
  const std::vector<std::pair<std::string, std::string>> patch = {
    {"Scene/Name", "patch"},
    {"Scene/Patch/Pressure", "2.5"},
    {"Scene/Patch/Upper body subdivisions", "3, 2"},
    {"Scene/Patch/Lower body subdivisions", "10, 4"},
    {"Contact/Friction coefficient", "0"},
    {"Adaptation/Target error", "2"}};
  const std::vector<std::pair<std::string, std::string>> blocks = {
    {"Scene/Name", "blocks"},
    {"Scene/Blocks/Upper body subdivisions", "4, 3"},
    {"Scene/Blocks/Hold centre line", "true"},
    {"Contact/Friction coefficient", "0"},
    {"Adaptation/Target error", "2"}};
  // The tolerance is relative to 2 U_h on the patch test (e = 0) and to
  // e^2 on blocks. Frictionless contact leaves 2 int (lambda_h -
  // lambda_ref) [u_h]_n out of the identity: zero where the interface
  // nodes of both bodies match (quadrilaterals, hierarchically refined),
  // the order of the contact work where they do not (triangles remeshed
  // independently per body).
  struct Case
  {
    std::string                                      name;
    std::string                                      cell_type;
    std::vector<std::pair<std::string, std::string>> settings;
    unsigned int                                     n_adaptations;
    double                                           tolerance;
  };
  for (const Case &c :
       {Case{"patch", "quadrilateral", patch, 0, 1e-10},
        Case{"patch", "triangle", patch, 0, 1e-10},
        Case{"blocks, mu = 0, adapted", "quadrilateral", blocks, 1, 1e-8},
        Case{"blocks, mu = 0, adapted", "triangle", blocks, 1, 4e-2}})
    {
      auto settings = c.settings;
      settings.push_back({"Mesh/Cell type", c.cell_type});
      settings.push_back({"Adaptation/Strategy",
                          c.cell_type == "triangle" ? "remesh" : "refine"});
      const auto p = solved_problem(settings, c.n_adaptations);
      const ReferenceSolutionStress reference(
        *p->scene, p->parameters, p->pointers(), 2, false);
      const StressDifference d =
        compare_stresses(p->pointers(), p->solutions(), reference, 4);
      double energy = 0, reference_energy = 0;
      for (unsigned int b = 0; b < 2; ++b)
        {
          energy += strain_energy(*p->bodies[b], p->bodies[b]->solution());
          reference_energy += reference.strain_energy(b);
        }
      const double twice_difference = 2 * (reference_energy - energy);
      const double scale =
        c.n_adaptations > 0 ? d.difference_squared : 2 * energy;
      const double mismatch =
        std::abs(d.difference_squared - twice_difference) / scale;
      out << "  " << c.cell_type << ", " << c.name << " (" << describe_mesh(*p)
          << "): U_h " << energy << ", U_ref " << reference_energy << ", e^2 "
          << d.difference_squared << ", 2 (U_ref - U_h) " << twice_difference
          << ", |difference| / " << (c.n_adaptations > 0 ? "e^2 " : "2 U_h ")
          << mismatch << "; epsilon "
          << std::sqrt(d.difference_squared / d.sum_squared)
          << ", epsilon_energy "
          << std::sqrt(std::max(0., reference_energy - energy) /
                       (4 * reference_energy))
          << std::endl;
      AssertThrow(mismatch <= c.tolerance,
                  ExcMessage(c.name + ": energy identity fails"));
    }
}
