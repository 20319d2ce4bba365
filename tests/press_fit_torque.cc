// A press fit that transmits a torque by friction, run from
// prm/press_fit_torque.prm: a hollow shaft (bore a0 = 5 mm, outer radius
// b = 10 mm) in a hub (bore a = b - delta, outer radius c = 20 mm,
// delta = 0.001 mm), E = 200 000 MPa, nu = 0.3, plane strain, mu = 0.3,
// P2. The hub's outer circle is clamped; the shaft's bore is turned by a
// prescribed rotation (Scene/Gmsh/Prescribed rotations) that grows over the
// load steps (Scene/Gmsh/Load steps), the interference there from step 1.
//
// The exact solution (testing::HeldPressFit): the radial and the torsion
// problems of the annuli are uncoupled, so the contact pressure is Lame's
// p for annuli held radially at a0 and c whatever the rotation; the
// interface sticks while the torque is below mu p 2 pi a^2, with the
// torque of the annuli's torsional stiffness, and slips everywhere at once
// when it reaches it; from then on the torque stays there. Checked at
// every load step:
//  - the nodal pressures against p (P2's tolerance of
//    tests/press_fit_quarter, 0.2 %);
//  - stick steps: every node sticks and the contact moment is the
//    torsional stiffness's torque (within 5e-4, the P2 torsion);
//  - slip steps: every node slips, the contact moment is mu times the
//    moment of the pressures, sum mu |x_j| D_jj p_j (to 1e-8: the slip
//    nodes' traction is mu p along the circle), and mu p 2 pi a^2 within
//    the tolerance of the pressures' mean deviation (1e-4);
//  - equilibrium: the reactions of the supports, from the FE stresses as
//    the virtual work of the rotation field on the supported DoFs
//    (integral of sigma(u_h) : eps(w_h), w_h the rotation about the origin
//    at the supported DoFs and zero elsewhere), balance the contact moment
//    to 1e-8: the hub's clamp (the slave side receives D lambda at its
//    nodes on the circle of radius a), the shaft's drive times a/b (the
//    master side receives M^T lambda at its nodes on the circle of radius
//    b, at the same angles: the lever arm is b, and the drive's moment is
//    b/a = 1 + 1.0e-4 times the contact moment).
// The 2-rank output is the same file: 1 and 2 ranks agree.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include "contact_test_utilities.h"
#include "lame_press_fit.h"

using namespace coulomb_adapt;

namespace
{
  // The moment about the origin that the supports of @p boundary_id exert
  // on the body: the virtual work of the FE stresses on the rotation field
  // w = (-y, x) at the DoFs of that boundary (zero at the others), which is
  // the reaction's moment since no load acts on the body's other DoFs
  // there.
  double
  reaction_moment(const ElasticBody &body, const types::boundary_id boundary_id)
  {
    const DoFHandler<2> &dofs = body.dof_handler();
    const auto          &fe   = dofs.get_fe();
    const IndexSet       supported =
      DoFTools::extract_boundary_dofs(dofs, ComponentMask(), {boundary_id});
    FEValues<2>                          fe_values(body.mapping(),
                          fe,
                          body.cell_quadrature(),
                          update_gradients | update_JxW_values);
    FEValues<2>                          support_values(body.mapping(),
                               fe,
                               Quadrature<2>(fe.get_unit_support_points()),
                               update_quadrature_points);
    const FEValuesExtractors::Vector     u(0);
    std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
    std::vector<SymmetricTensor<2, 2>>   strains(body.cell_quadrature().size());
    double                               moment = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          support_values.reinit(cell);
          cell->get_dof_indices(indices);
          fe_values[u].get_function_symmetric_gradients(body.solution(),
                                                        strains);
          for (unsigned int i = 0; i < indices.size(); ++i)
            {
              if (!supported.is_element(indices[i]))
                continue;
              const Point<2>     x = support_values.quadrature_point(i);
              const unsigned int component =
                fe.system_to_component_index(i).first;
              const double w = component == 0 ? -x[1] : x[0];
              for (unsigned int q = 0; q < strains.size(); ++q)
                moment += w *
                          (body.material().stress(strains[q]) *
                           fe_values[u].symmetric_gradient(i, q)) *
                          fe_values.JxW(q);
            }
        }
    return Utilities::MPI::sum(moment, MPI_COMM_WORLD);
  }



  // The boundary id of the body's Dirichlet condition (one per body here).
  types::boundary_id
  supported_boundary(const ElasticBody &body)
  {
    AssertThrow(body.description().dirichlet.size() == 1,
                ExcMessage("expected one Dirichlet condition per body"));
    return body.description().dirichlet[0].boundary_id;
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  const testing::HeldPressFit fit;
  const double                p       = fit.pressure();
  const double                mu      = 0.3;
  const double                theta   = 4e-4;
  const double                T_slip  = fit.full_slip_torque(mu);
  const unsigned int          n_steps = 4;
  out << std::setprecision(6)
      << "Lame's pressure, annuli held at a0 and c: p = " << p
      << " MPa; full-slip torque mu p 2 pi a^2 = " << T_slip
      << " N mm/mm; stick torque at the final rotation " << theta
      << " rad: " << fit.stick_torque(theta) << " N mm/mm" << std::endl;

  auto problem = testing::solve_contact_setup(
    {{"Scene/Gmsh/Mesh file",
      testing::example_file("meshes/press_fit_torque.geo")},
     {"Scene/Gmsh/Prescribed rotations",
      "shaft bore: " + Patterns::Tools::Convert<double>::to_string(theta)},
     {"Scene/Gmsh/Load steps", std::to_string(n_steps)},
     {"Contact/Friction coefficient", "0.3"}},
    testing::example_file("press_fit_torque.prm"));
  const Scene &scene = *problem->scene;
  AssertThrow(scene.n_load_steps() == n_steps,
              ExcMessage("the scene's load steps are not 'Load steps'"));
  const types::boundary_id clamp = supported_boundary(*problem->bodies[0]);
  const types::boundary_id drive = supported_boundary(*problem->bodies[1]);

  for (unsigned int step = 1; step <= n_steps; ++step)
    {
      scene.set_load_step(step);
      for (auto &body : problem->bodies)
        {
          body->setup_system();
          body->assemble_system();
        }
      const ContactSolverReport report = problem->solver->solve();
      const auto               &states = problem->solver->node_states();

      double       deviation = 0, force = 0, length = 0, slip_moment = 0;
      unsigned int n_stick = 0, n_slip = 0;
      for (const auto &s : states)
        {
          n_stick += s.status == ContactStatus::stick;
          n_slip += s.status == ContactStatus::slip;
          deviation = std::max(deviation, std::abs(s.pressure - p) / p);
          force += s.pressure * s.weight;
          length += s.weight;
          slip_moment += mu * s.position.norm() * s.weight * s.pressure;
        }
      const double mean_deviation = force / length / p - 1;
      const double M_contact      = report.contact_moment;
      const double M_clamp        = reaction_moment(*problem->bodies[0], clamp);
      const double M_drive        = reaction_moment(*problem->bodies[1], drive);
      const double clamp_balance  = std::abs(M_contact + M_clamp) / M_contact;
      const double a              = fit.b - fit.delta;
      const double drive_balance =
        std::abs(M_drive - M_contact * fit.b / a) / M_contact;
      const bool   all_stick = n_stick == states.size();
      const bool   all_slip  = n_slip == states.size();
      const double rotation  = theta * step / n_steps;
      const double exact =
        all_stick ? fit.stick_torque(rotation) : fit.full_slip_torque(mu);
      const double torque_deviation = M_contact / exact - 1;

      out << "load step " << step << "/" << n_steps << ", rotation "
          << std::setprecision(3) << rotation << " rad: " << states.size()
          << " slave nodes, " << n_stick << " stick, " << n_slip
          << " slip; Newton steps in [1, 12]: "
          << (report.newton_iterations >= 1 && report.newton_iterations <= 12 ?
                "yes" :
                "NO")
          << std::endl
          << "  pressure: largest deviation from p " << std::setprecision(2)
          << 100 * deviation
          << " % (within 0.2 %: " << (deviation < 2e-3 ? "yes" : "no")
          << "), mean " << std::scientific << std::setprecision(1)
          << mean_deviation << std::defaultfloat << std::endl
          << "  contact moment on the hub " << std::setprecision(5) << M_contact
          << " N mm/mm, " << (all_stick ? "stick torque" : "mu p 2 pi a^2")
          << " " << exact << ": deviation " << std::scientific
          << std::setprecision(1) << torque_deviation << std::defaultfloat
          << std::endl
          << "  moments balance: hub clamp "
          << (clamp_balance < 1e-8 ? "below 1e-8" : "ABOVE 1e-8")
          << ", shaft drive (times a/b) "
          << (drive_balance < 1e-8 ? "below 1e-8" : "ABOVE 1e-8")
          << "; drive / contact moment - 1 = " << std::scientific
          << std::setprecision(2) << M_drive / M_contact - 1
          << std::defaultfloat << std::endl;
      if (all_slip)
        out << "  mu sum |x_j| D_jj p_j: the contact moment to "
            << (std::abs(M_contact / slip_moment - 1) < 1e-8 ? "1e-8" :
                                                               "MORE than 1e-8")
            << std::endl;

      AssertThrow(all_stick || all_slip,
                  ExcMessage("the interface must stick or slip as a whole"));
      AssertThrow(step > 1 || all_stick,
                  ExcMessage("the first step must stick"));
      AssertThrow(step == 1 || all_slip,
                  ExcMessage("the later steps must slip"));
      AssertThrow(deviation < 2e-3 && std::abs(mean_deviation) < 1e-4,
                  ExcMessage("pressure off Lame's by " +
                             std::to_string(deviation)));
      AssertThrow(std::abs(torque_deviation) < (all_stick ? 5e-4 : 1e-4),
                  ExcMessage("torque off by " +
                             std::to_string(torque_deviation)));
      AssertThrow(!all_slip || std::abs(M_contact / slip_moment - 1) < 1e-8,
                  ExcMessage("the slip torque is not mu times the moment "
                             "of the pressures"));
      AssertThrow(clamp_balance < 1e-8 && drive_balance < 1e-8,
                  ExcMessage("moments do not balance: clamp " +
                             std::to_string(clamp_balance) + ", drive " +
                             std::to_string(drive_balance)));
      AssertThrow(report.newton_iterations >= 1 &&
                    report.newton_iterations <= 12,
                  ExcMessage("Newton steps out of range"));
    }
}
