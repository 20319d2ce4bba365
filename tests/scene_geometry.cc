// The built-in scenes' meshes, on quadrilaterals and on triangles: area of
// each body, length of each boundary part, and whether a body is held by
// its Dirichlet data alone, checked against the geometry of theory.md;
// symmetry lines (hertz 'Hold axis', blocks and punch 'Hold centre line')
// hold the upper body sideways on every mesh, remeshed ones included.

#include <deal.II/fe/fe_values.h>

#include <coulomb_adapt/adaptation/gmsh_remesher.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/rigid_motion_gram.h>
#include <coulomb_adapt/scenes/hertz.h>
#include <coulomb_adapt/scenes/scene_factory.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include "test_utilities.h"

#include <map>

using namespace coulomb_adapt;

struct Expected
{
  double                               area;
  std::map<types::boundary_id, double> lengths;
  bool                                 floating;
  double                               tolerance; // relative
};

void
check(const std::string             &scene_name,
      const std::string             &cell_type,
      const std::array<Expected, 2> &expected)
{
  ParameterHandler prm;
  const Parameters parameters = testing::make_parameters(
    prm, {{"Scene/Name", scene_name}, {"Mesh/Cell type", cell_type}});
  const auto     scene = scenes::create_scene(parameters, prm);
  auto           out   = testing::root_output();
  const MPI_Comm comm  = MPI_COMM_WORLD;

  for (unsigned int b = 0; b < 2; ++b)
    {
      ElasticBody body(comm,
                       *scene,
                       b,
                       parameters.mesh.cell_type,
                       0,
                       parameters.finite_elements);
      body.setup_system();

      FEValues<2>                          fe_values(body.mapping(),
                            body.dof_handler().get_fe(),
                            body.cell_quadrature(),
                            update_JxW_values);
      double                               area = 0;
      std::map<types::boundary_id, double> lengths;
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              area += fe_values.JxW(q);
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary())
                lengths[face->boundary_id()] += face->measure();
          }
      area = Utilities::MPI::sum(area, comm);

      out << scene_name << " (" << cell_type << "), body " << b + 1 << " ("
          << body.name()
          << "): " << body.triangulation().n_global_active_cells()
          << " cells, area " << std::setprecision(6) << area;
      const Expected &e = expected[b];
      AssertThrow(std::abs(area - e.area) < e.tolerance * e.area,
                  ExcMessage("area " + std::to_string(area)));
      for (const auto &[id, length] : e.lengths)
        {
          const double l = Utilities::MPI::sum(lengths[id], comm);
          out << ", boundary " << int(id) << " length " << l;
          AssertThrow(std::abs(l - length) < e.tolerance * length,
                      ExcMessage("boundary " + std::to_string(id) + " length " +
                                 std::to_string(l)));
        }
      const bool floating = body.is_floating();
      out << ", floating: " << (floating ? "yes" : "no") << std::endl;
      AssertThrow(floating == e.floating, ExcMessage("floating"));
    }
}

// The Hertz meshes must resolve the contact zone: at least 20 contact
// faces of each body across [-a, a] with the default parameters.
void
check_hertz_resolution(const std::string &cell_type)
{
  ParameterHandler prm;
  const Parameters parameters = testing::make_parameters(
    prm, {{"Scene/Name", "hertz"}, {"Mesh/Cell type", cell_type}});
  const auto   scene = scenes::create_scene(parameters, prm);
  const double a =
    dynamic_cast<const scenes::Hertz &>(*scene).contact_half_width();
  auto out = testing::root_output();
  for (unsigned int b = 0; b < 2; ++b)
    {
      ElasticBody  body(MPI_COMM_WORLD,
                       *scene,
                       b,
                       parameters.mesh.cell_type,
                       0,
                       parameters.finite_elements);
      double       covered = 0;
      unsigned int n_faces = 0;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() &&
                face->boundary_id() == boundary_ids::contact &&
                std::abs(face->center()[0]) < a)
              {
                ++n_faces;
                covered += face->measure();
              }
      n_faces = Utilities::MPI::sum(n_faces, MPI_COMM_WORLD);
      out << "hertz (" << cell_type << "), body " << b + 1
          << ": at least 20 contact faces across the contact width 2a: "
          << (n_faces >= 20 ? "yes" : "no") << std::endl;
      AssertThrow(n_faces >= 20,
                  ExcMessage(std::to_string(n_faces) +
                             " contact faces in [-a, a]"));
    }
}

// A symmetry line must select nodes, on the scene's mesh and on a mesh
// that gmsh made from its boundary: the gmsh meshes of the hertz disc had
// no nodes on the axis, and 'Hold axis' held nothing.
void
check_symmetry_line(const std::string &scene_name,
                    const std::string &cell_type,
                    const std::string &hold_parameter)
{
  ParameterHandler prm;
  const Parameters parameters =
    testing::make_parameters(prm,
                             {{"Scene/Name", scene_name},
                              {"Mesh/Cell type", cell_type},
                              {hold_parameter, "true"}});
  const auto  scene = scenes::create_scene(parameters, prm);
  auto        out   = testing::root_output();
  ElasticBody body(MPI_COMM_WORLD,
                   *scene,
                   0,
                   parameters.mesh.cell_type,
                   0,
                   parameters.finite_elements);
  body.setup_system();
  const Tensor<1, 2> sideways({1., 0.});
  const auto         held_sideways = [&]() {
    return holds_translation_along(body.support_gram(Point<2>()), sideways);
  };
  out << scene_name << " (" << cell_type
      << "), body 1 held sideways: " << (held_sideways() ? "yes" : "no");
  AssertThrow(held_sideways(), ExcMessage(hold_parameter + " holds nothing"));
  if (cell_type == "triangle")
    {
      // Remeshed with cells about half the size.
      Vector<double> ratio(body.triangulation().n_active_cells());
      ratio                  = 0.5;
      const auto       field = nodal_size_field(body, ratio);
      Triangulation<2> geometry;
      body.create_scene_coarse_mesh(geometry);
      const auto lines = body.description().interior_lines();
      AssertThrow(lines.size() == 1, ExcMessage("no interior line"));
      body.replace_mesh(remesh_with_gmsh(geometry,
                                         field,
                                         body.name(),
                                         MPI_COMM_WORLD,
                                         RemeshingAlgorithm::frontal_delaunay,
                                         lines));
      body.setup_system();
      out << ", after remeshing: " << (held_sideways() ? "yes" : "no");
      AssertThrow(held_sideways(),
                  ExcMessage(hold_parameter + " holds nothing after "
                                              "remeshing"));
    }
  out << std::endl;
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using namespace boundary_ids;
  const double pi = numbers::PI;

  for (const std::string cell_type : {"quadrilateral", "triangle"})
    {
      check("blocks",
            cell_type,
            {{{1e4,
               {{contact, 100.}, {traction, 100.}, {traction_free, 200.}},
               true,
               1e-12},
              {4e4,
               {{contact, 200.}, {dirichlet, 200.}, {traction_free, 400.}},
               false,
               1e-12}}});
      check("patch",
            cell_type,
            {{{50., {{contact, 10.}, {traction, 10.}}, true, 1e-12},
              {50., {{contact, 10.}, {roller, 10.}}, false, 1e-12}}});
      check("punch",
            cell_type,
            {{{200., {{contact, 20.}, {traction, 20.}}, true, 1e-12},
              {5000., {{contact, 100.}, {dirichlet, 100.}}, false, 1e-12}}});
      check("manufactured",
            cell_type,
            {{{1., {{dirichlet, 3.}, {traction, 1.}}, false, 1e-12},
              {1., {{dirichlet, 3.}, {traction, 1.}}, false, 1e-12}}});
    }
  // The half disc is a polygon inscribed in the circle: its area and arc
  // length converge to pi R^2 / 2 and pi R as the mesh is refined; the
  // contact refinements resolve the arc near the contact point only.
  for (const std::string cell_type : {"quadrilateral", "triangle"})
    {
      check(
        "hertz",
        cell_type,
        {{{pi * 1e4 / 2, {{contact, pi * 100}, {traction, 200.}}, true, 2e-2},
          {2e4, {{contact, 200.}, {dirichlet, 200.}}, false, 1e-12}}});
      check_hertz_resolution(cell_type);
      check_symmetry_line("hertz", cell_type, "Scene/Hertz/Hold axis");
      check_symmetry_line("blocks", cell_type, "Scene/Blocks/Hold centre line");
      check_symmetry_line("punch", cell_type, "Scene/Punch/Hold centre line");
    }
}
