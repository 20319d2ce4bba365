// Scene/Gmsh/Tangential tractions, the traction s t along the boundary's
// tangent t = (-n_y, n_x), against what it must equal:
//  1. on a straight edge it is a traction vector: on prm/blocks_gmsh.prm's
//     loaded top (outward normal (0, 1), t = (-1, 0)) 'Normal pressures =
//     loaded top: 10' with 'Tangential tractions = loaded top: 2' gives the
//     contact tractions of 'Tractions = loaded top: -2; -10' (to
//     round-off);
//  2. on a circle it turns: prm/press_fit_torque.prm (P1) with the shaft as
//     body 1 and no drive but 'Tangential tractions = shaft bore: -13.5'
//     (t runs clockwise around the bore, a hole of the shaft: -13.5 MPa
//     turns the shaft counterclockwise). Nothing else holds the shaft, so
//     the moment of the contact tractions on it balances the applied
//     moment, the integral of x × (s t) over the bore computed here by
//     quadrature on the mesh's faces (to 1e-10). The torque is 0.97 of the
//     slip torque mu p 2 pi b^2 (p Lame's for the shaft free at its bore
//     and the hub clamped outside, 11.58 MPa: s = 13.90 MPa at the limit),
//     so every node sticks. Beyond it (1.03 of the limit, or in load steps
//     up to 1.4 of it) the program stops with its sliding diagnosis
//     (tests/bad_input, torque_beyond_slip*).

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include "contact_test_utilities.h"

using namespace coulomb_adapt;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();

  out << "1. tangential traction 2 MPa and normal pressure 10 MPa on a "
         "straight edge against the traction (-2, -10) MPa"
      << std::endl;
  {
    const std::string prm = testing::example_file("blocks_gmsh.prm");
    const std::string geo =
      testing::example_file("meshes/blocks_structured.geo");
    const auto vector_load =
      testing::solve_contact({{"Scene/Gmsh/Mesh file", geo},
                              {"Scene/Gmsh/Tractions", "loaded top: -2; -10"}},
                             prm);
    const auto tangential_load =
      testing::solve_contact({{"Scene/Gmsh/Mesh file", geo},
                              {"Scene/Gmsh/Tractions", ""},
                              {"Scene/Gmsh/Normal pressures", "loaded top: 10"},
                              {"Scene/Gmsh/Tangential tractions",
                               "loaded top: 2"}},
                             prm);
    const auto  &s          = vector_load->solver->node_states();
    const auto  &t          = tangential_load->solver->node_states();
    const double difference = testing::relative_traction_difference(s, t);
    unsigned int n_stick = 0, n_slip = 0;
    for (unsigned int j = 0; j < s.size(); ++j)
      {
        AssertThrow(s[j].status == t[j].status,
                    ExcMessage("different contact states"));
        n_stick += s[j].status == ContactStatus::stick;
        n_slip += s[j].status == ContactStatus::slip;
      }
    out << "  " << n_stick << " stick, " << n_slip
        << " slip nodes in both; contact force (" << std::setprecision(8)
        << tangential_load->report.contact_force[0] << ", "
        << tangential_load->report.contact_force[1]
        << ") N/mm; same states and tractions to 1e-12 of the largest "
           "pressure: "
        << (difference < 1e-12 ? "yes" : "no") << std::endl;
    AssertThrow(difference < 1e-12,
                ExcMessage("a tangential traction on a straight edge is not "
                           "the traction vector: " +
                           std::to_string(difference)));
  }

  out << "2. tangential traction -13.5 MPa on the shaft's bore (0.97 of the "
         "slip limit)"
      << std::endl;
  {
    const double s       = -13.5;
    auto         problem = testing::solve_contact(
      {{"Scene/Gmsh/Mesh file",
                testing::example_file("meshes/press_fit_torque.geo")},
               {"Finite elements/Polynomial degree", "1"},
               {"Scene/Gmsh/Prescribed rotations", ""},
               {"Scene/Gmsh/Tangential tractions", "shaft bore: -13.5"},
               {"Scene/Gmsh/Load steps", "1"},
               {"Scene/Gmsh/Contact pair", "shaft surface, hub bore"},
               {"Scene/Gmsh/Body 1/Physical surfaces", "shaft"},
               {"Scene/Gmsh/Body 2/Physical surfaces", "hub"}},
      testing::example_file("press_fit_torque.prm"));
    const ElasticBody &shaft = *problem->bodies[0];

    // The applied moment about the origin, by quadrature over the faces
    // of the bore (the shaft's boundary faces nearer the origin than its
    // outer surface).
    const QGauss<1> quadrature(3);
    FEFaceValues<2> face_values(shaft.mapping(),
                                shaft.dof_handler().get_fe(),
                                quadrature,
                                update_quadrature_points |
                                  update_normal_vectors | update_JxW_values);
    double          applied = 0;
    for (const auto &cell : shaft.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->center().norm() < 7.5)
            {
              face_values.reinit(cell, face);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                {
                  const Point<2>     &x = face_values.quadrature_point(q);
                  const Tensor<1, 2> &n = face_values.normal_vector(q);
                  const Tensor<1, 2>  traction({-s * n[1], s * n[0]});
                  applied += (x[0] * traction[1] - x[1] * traction[0]) *
                             face_values.JxW(q);
                }
            }
    applied = Utilities::MPI::sum(applied, MPI_COMM_WORLD);

    const auto  &states  = problem->solver->node_states();
    unsigned int n_stick = 0;
    for (const auto &state : states)
      n_stick += state.status == ContactStatus::stick;
    const double M       = problem->report.contact_moment;
    const double balance = std::abs(M + applied) / std::abs(applied);
    out << "  applied moment " << std::setprecision(6) << applied
        << " N mm/mm (s 2 pi a0^2 = " << -s * 2 * numbers::PI * 25
        << "), contact moment on the shaft " << M
        << "; balance to 1e-10: " << (balance < 1e-10 ? "yes" : "no")
        << std::endl
        << "  " << states.size() << " slave nodes, " << n_stick
        << " stick: all stick: " << (n_stick == states.size() ? "yes" : "no")
        << std::endl;
    AssertThrow(balance < 1e-10,
                ExcMessage("moments do not balance: " +
                           std::to_string(balance)));
    AssertThrow(applied > 0, ExcMessage("s < 0 must turn counterclockwise"));
    AssertThrow(n_stick == states.size(),
                ExcMessage("below the slip limit every node sticks"));
  }
}
