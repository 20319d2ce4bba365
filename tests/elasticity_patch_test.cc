// Constant-stress patch test: a linear displacement field (constant strain
// and stress) imposed through Dirichlet data and the matching traction must
// be reproduced exactly, to round-off, on (1) a randomly distorted
// quadrilateral mesh and (2) the unstructured triangle meshes gmsh makes of
// tests/data/two_squares.geo (both bodies), for degrees 1 and 2.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/elasticity_errors.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene_meshes.h>

#include "test_utilities.h"

using namespace coulomb_adapt;

// u = G x with a general (non-symmetric) gradient G.
class LinearDisplacement : public Function<2>
{
public:
  LinearDisplacement()
    : Function<2>(2)
  {
    gradient_[0] = Tensor<1, 2>({1.0e-3, -0.4e-3});
    gradient_[1] = Tensor<1, 2>({0.7e-3, -2.0e-3});
  }
  double
  value(const Point<2> &p, const unsigned int c) const override
  {
    return gradient_[c] * p;
  }
  Tensor<1, 2>
  gradient(const Point<2> &, const unsigned int c) const override
  {
    return gradient_[c];
  }
  Tensor<2, 2> gradient_;
};

// A scene for one test mesh: the linear field on every boundary but the
// one marked 'traction', where sigma n is applied.
class PatchScene : public Scene
{
public:
  PatchScene(std::function<void(unsigned int, Triangulation<2> &)> make_mesh)
    : make_mesh(make_mesh)
  {}
  std::string
  name() const override
  {
    return "patch test";
  }
  void
  create_coarse_mesh(const unsigned int body,
                     const CellType,
                     Triangulation<2> &tria) const override
  {
    make_mesh(body, tria);
  }
  BodyDescription
  describe_body(const unsigned int body) const override
  {
    BodyDescription d;
    d.name               = "body " + std::to_string(body + 1);
    d.material           = {body == 0 ? 1000. : 3000., body == 0 ? 0.3 : 0.45};
    auto u               = std::make_shared<LinearDisplacement>();
    d.exact_displacement = u;
    for (const auto id : {boundary_ids::traction_free,
                          boundary_ids::contact,
                          boundary_ids::dirichlet})
      d.dirichlet.push_back({id, ComponentMask(2, true), u});
    const ElasticMaterial       material(d.material, PlaneModel::plane_strain);
    const SymmetricTensor<2, 2> stress =
      material.stress(symmetrize(u->gradient_));
    d.tractions.push_back({boundary_ids::traction,
                           [stress](const Point<2> &, const Tensor<1, 2> &n) {
                             return stress * n;
                           }});
    return d;
  }

private:
  std::function<void(unsigned int, Triangulation<2> &)> make_mesh;
};

void
check(const std::string &label, const Scene &scene, const unsigned int n_bodies)
{
  auto out = testing::root_output();
  for (const unsigned int degree : {1u, 2u})
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        parameters::FiniteElements fe{degree, PlaneModel::plane_strain};
        parameters::LinearSolver   solver{
          LinearSolverType::direct, 0, "Amesos_Mumps", 1e-12, 100, 0};
        ElasticBody body(
          MPI_COMM_WORLD, scene, b, CellType::quadrilateral, 0, fe);
        body.setup_system();
        body.assemble_system();
        body.solve(solver);
        const ElasticityErrors e =
          compute_elasticity_errors(body,
                                    *body.description().exact_displacement);
        const double relative_energy_error = e.energy / e.energy_of_exact;
        out << label << ", degree " << degree << ", body " << b + 1 << ": "
            << body.triangulation().n_global_active_cells()
            << " cells, relative energy error below 1e-12: "
            << (relative_energy_error < 1e-12 ? "yes" : "no") << std::endl;
        AssertThrow(relative_energy_error < 1e-12,
                    ExcMessage(label +
                               ": patch test failed, relative energy "
                               "error " +
                               std::to_string(relative_energy_error)));
      }
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  const PatchScene distorted_quads([](unsigned int, Triangulation<2> &tria) {
    make_rectangle(tria,
                   Point<2>(0, 0),
                   Point<2>(2, 1),
                   {6, 4},
                   {{boundary_ids::dirichlet,
                     boundary_ids::dirichlet,
                     boundary_ids::dirichlet,
                     boundary_ids::traction}},
                   CellType::quadrilateral);
    // Move interior vertices by up to 30 % of the local edge length.
    GridTools::distort_random(0.3, tria, true, 42);
  });
  check("distorted quadrilaterals", distorted_quads, 1);

  const auto meshes =
    read_two_body_gmsh_file(std::string(COULOMB_ADAPT_TEST_DATA_DIR) +
                              "/two_squares.geo",
                            CellType::triangle,
                            1.0);
  const PatchScene gmsh_triangles(
    [&meshes](unsigned int body, Triangulation<2> &tria) {
      meshes[body].create_triangulation(tria);
    });
  check("gmsh triangles", gmsh_triangles, 2);
}
