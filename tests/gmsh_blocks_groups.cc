// The gmsh scene's per-group conditions against the built-in 'blocks'
// scene (theory.md section 5) on the same meshes, mu = 0.3:
//  1. quadrilaterals: prm/blocks_gmsh.prm (prm/meshes/blocks_structured.geo,
//     structured 4 x 4 and 8 x 8 cells, the built-in default) against the
//     same file run with Scene/Name = blocks;
//  2. triangles: the seed's mesh of prm/blocks.prm (3 x 3 and 6 x 7
//     rectangles cut into triangles) written from the built-in scene to a
//     .msh file with named physical groups, read back by the gmsh scene
//     with the entries of prm/blocks_gmsh.prm;
//  3. the old syntax (groups 'dirichlet', 'traction', 'contact' and the
//     'Traction' entry) against the new entries on prm/meshes/blocks.geo.
// Compared: the contact nodes (positions, stick/slip/open states, pressure,
// tangential traction, gap, slip), the contact force, each body's strain
// energy and the displacement at three points. The meshes' cells and DoFs
// are numbered differently in 1 and 2, so the numbers agree to round-off
// (1e-10 relative asked); in 3 the meshes are the same and so is every
// number (to the last bit).

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include "contact_test_utilities.h"

#include <fstream>

using namespace coulomb_adapt;

namespace
{
  // The largest difference between two solutions, relative to the size of
  // each compared quantity.
  double
  difference(const testing::SolvedContactProblem &a,
             const testing::SolvedContactProblem &b,
             ConditionalOStream                  &out)
  {
    const auto &s = a.solver->node_states();
    const auto &t = b.solver->node_states();
    AssertThrow(s.size() == t.size(),
                ExcMessage("different numbers of contact nodes: " +
                           std::to_string(s.size()) + ", " +
                           std::to_string(t.size())));
    double p_max = 0, u_scale = 0;
    for (const auto &n : s)
      p_max = std::max(p_max, n.pressure);
    double       traction = 0, kinematics = 0, position = 0;
    unsigned int n_same_state = 0;
    for (unsigned int j = 0; j < s.size(); ++j)
      {
        position = std::max(position, s[j].position.distance(t[j].position));
        n_same_state += s[j].status == t[j].status;
        traction = std::max(
          {traction,
           std::abs(s[j].pressure - t[j].pressure),
           std::abs(s[j].tangential_traction - t[j].tangential_traction)});
        kinematics = std::max({kinematics,
                               std::abs(s[j].gap - t[j].gap),
                               std::abs(s[j].slip - t[j].slip)});
      }
    double worst = std::max(position / 100, traction / p_max);
    worst        = std::max(worst,
                     (a.report.contact_force - b.report.contact_force).norm() /
                       a.report.contact_force.norm());
    for (unsigned int k = 0; k < 2; ++k)
      {
        const double ea = strain_energy(*a.bodies[k], a.bodies[k]->solution());
        const double eb = strain_energy(*b.bodies[k], b.bodies[k]->solution());
        worst           = std::max(worst, std::abs(ea - eb) / ea);
      }
    for (const auto &[k, x] : {std::pair(0u, Point<2>(100, 300)),
                               std::pair(0u, Point<2>(150, 200)),
                               std::pair(1u, Point<2>(200, 200))})
      {
        Vector<double> ua(2), ub(2);
        VectorTools::point_value(a.bodies[k]->mapping(),
                                 a.bodies[k]->dof_handler(),
                                 a.bodies[k]->solution(),
                                 x,
                                 ua);
        VectorTools::point_value(b.bodies[k]->mapping(),
                                 b.bodies[k]->dof_handler(),
                                 b.bodies[k]->solution(),
                                 x,
                                 ub);
        ua -= ub;
        u_scale = std::max(u_scale, ub.l2_norm());
        worst   = std::max(worst, ua.l2_norm() / u_scale);
      }
    worst = std::max(worst, kinematics / u_scale);
    out << "  " << s.size() << " contact nodes, " << n_same_state
        << " in the same state; vertical contact force " << std::setprecision(8)
        << a.report.contact_force[1] << " N/mm, max pressure " << p_max
        << " MPa" << std::endl;
    AssertThrow(n_same_state == s.size(), ExcMessage("the sets differ"));
    return worst;
  }



  // The built-in scene's meshes as a gmsh file with the groups of
  // prm/meshes/blocks_structured.geo.
  void
  write_blocks_msh(const testing::SolvedContactProblem &builtin,
                   const std::string                   &file_name)
  {
    std::ofstream f(file_name);
    f << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
      << "$PhysicalNames\n6\n"
      << "1 1 \"base\"\n1 2 \"loaded top\"\n1 3 \"upper block bottom\"\n"
      << "1 4 \"lower block top\"\n2 5 \"upper block\"\n2 6 \"lower "
         "block\"\n$EndPhysicalNames\n";
    // Boundary id -> physical group, per body.
    const std::array<std::map<types::boundary_id, int>, 2> group = {
      {{{boundary_ids::traction, 2}, {boundary_ids::contact, 3}},
       {{boundary_ids::dirichlet, 1}, {boundary_ids::contact, 4}}}};
    std::ostringstream nodes, elements;
    unsigned int       n_nodes = 0, n_elements = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        const auto        &tria   = builtin.bodies[b]->triangulation();
        const unsigned int offset = n_nodes;
        for (const auto &x : tria.get_vertices())
          nodes << ++n_nodes << ' ' << std::setprecision(17) << x[0] << ' '
                << x[1] << " 0\n";
        for (const auto &cell : tria.active_cell_iterators())
          {
            elements << ++n_elements << (cell->n_vertices() == 3 ? " 2" : " 3")
                     << " 2 " << 5 + b << ' ' << 5 + b;
            // gmsh numbers a quadrangle's corners around it.
            const std::vector<unsigned int> order =
              cell->n_vertices() == 3 ? std::vector<unsigned int>{0, 1, 2} :
                                        std::vector<unsigned int>{0, 1, 3, 2};
            for (const unsigned int v : order)
              elements << ' ' << offset + cell->vertex_index(v) + 1;
            elements << '\n';
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() &&
                  group[b].count(face->boundary_id()) > 0)
                {
                  const int g = group[b].at(face->boundary_id());
                  elements << ++n_elements << " 1 2 " << g << ' ' << g << ' '
                           << offset + face->vertex_index(0) + 1 << ' '
                           << offset + face->vertex_index(1) + 1 << '\n';
                }
          }
      }
    f << "$Nodes\n"
      << n_nodes << '\n'
      << nodes.str() << "$EndNodes\n$Elements\n"
      << n_elements << '\n'
      << elements.str() << "$EndElements\n";
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  auto                             out = testing::root_output();
  const std::string groups_prm = testing::example_file("blocks_gmsh.prm");

  out << "1. quadrilaterals, prm/blocks_gmsh.prm against Scene/Name = blocks"
      << std::endl;
  {
    const auto gmsh =
      testing::solve_example("blocks_gmsh.prm", "blocks_structured.geo");
    const auto builtin =
      testing::solve_contact({{"Scene/Name", "blocks"}}, groups_prm);
    const double d = difference(*builtin, *gmsh, out);
    out << "  same numbers to 1e-10: " << (d < 1e-10 ? "yes" : "no")
        << std::endl;
    AssertThrow(d < 1e-10, ExcMessage("differ by " + std::to_string(d)));
  }

  out << "2. triangles, the seed's mesh of prm/blocks.prm written to .msh"
      << std::endl;
  {
    const std::vector<std::pair<std::string, std::string>> seed_mesh = {
      {"Scene/Blocks/Upper body subdivisions", "3, 3"},
      {"Scene/Blocks/Lower body subdivisions", "6, 7"},
      {"Mesh/Cell type", "triangle"}};
    auto builtin_settings = seed_mesh;
    builtin_settings.emplace_back("Scene/Name", "blocks");
    const auto builtin = testing::solve_contact(builtin_settings, groups_prm);
    write_blocks_msh(*builtin, "blocks_seed_mesh.msh");
    auto gmsh_settings = seed_mesh;
    gmsh_settings.emplace_back("Scene/Gmsh/Mesh file", "blocks_seed_mesh.msh");
    const auto   gmsh = testing::solve_contact(gmsh_settings, groups_prm);
    const double d    = difference(*builtin, *gmsh, out);
    out << "  same numbers to 1e-10: " << (d < 1e-10 ? "yes" : "no")
        << std::endl;
    AssertThrow(d < 1e-10, ExcMessage("differ by " + std::to_string(d)));
  }

  out << "3. old syntax against the per-group entries, prm/meshes/blocks.geo"
      << std::endl;
  {
    const std::string geo = testing::example_file("meshes/blocks.geo");
    const auto        old = testing::solve_contact({{"Scene/Name", "gmsh"},
                                                    {"Scene/Gmsh/Mesh file", geo},
                                                    {"Mesh/Cell type", "triangle"}});
    const auto        grouped =
      testing::solve_contact({{"Scene/Name", "gmsh"},
                              {"Scene/Gmsh/Mesh file", geo},
                              {"Scene/Gmsh/Fixed components", "dirichlet: x y"},
                              {"Scene/Gmsh/Tractions", "traction: 0; -10"},
                              {"Scene/Gmsh/Contact pair", "contact, contact"},
                              {"Mesh/Cell type", "triangle"}});
    const double d = difference(*old, *grouped, out);
    const double u =
      testing::relative_difference(testing::displacements(*old),
                                   testing::displacements(*grouped));
    out << "  identical: " << (d == 0 && u == 0 ? "yes" : "no") << std::endl;
    AssertThrow(d == 0 && u == 0,
                ExcMessage("differ by " + std::to_string(d) + ", " +
                           std::to_string(u)));
  }
}
