#ifndef coulomb_adapt_bodies_elastic_body_h
#define coulomb_adapt_bodies_elastic_body_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/grid/cell_id.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/core/elastic_material.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/scenes/gmsh_reader.h>
#include <coulomb_adapt/scenes/scene.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <memory>
#include <optional>
#include <set>

namespace coulomb_adapt
{
  /** Throw if a cell of @p mesh (of body @p body_index, @p name) has a
   * vertex that is not a finite number or no area (a repeated node, a
   * zero-area triangle): its stiffness would be singular or non-finite. */
  void
  check_mesh_cells(const Triangulation<2> &mesh,
                   const std::string      &name,
                   const unsigned int      body_index);

  /**
   * One linear elastic body: its distributed mesh, finite element space,
   * constraints (hanging nodes, Dirichlet data) and elasticity system.
   *
   * Quadrilateral meshes live in a parallel::distributed::Triangulation
   * (p4est) and are refined in place. Triangle meshes live in a
   * parallel::fullydistributed::Triangulation, the distributed
   * triangulation deal.II 9.4 offers for simplices; it cannot be refined,
   * so a refined triangle mesh is rebuilt from the serial coarse mesh.
   * Serial runs are the one-rank case of the same code.
   */
  class ElasticBody
  {
  public:
    /**
     * Build the mesh of body @p body_index of @p scene: its coarse mesh,
     * the scene's local refinement (quadrilaterals), then
     * @p global_refinements uniform refinements.
     */
    ElasticBody(const MPI_Comm                    mpi_communicator,
                const Scene                      &scene,
                const unsigned int                body_index,
                const CellType                    cell_type,
                const unsigned int                global_refinements,
                const parameters::FiniteElements &fe_parameters);

    ~ElasticBody();

    /** Refine every cell once. */
    void
    refine_uniformly();

    /** Refine k times (+k) and coarsen (-1) the locally owned active cells
     * as @p decisions says (indexed by active cell index); hanging nodes
     * are kept at one level by p4est. Quadrilateral meshes only. */
    void
    refine_and_coarsen(const std::vector<signed char> &decisions);

    /** The cells of this mesh of a level below @p below_level that have
     * children, on every rank: the hierarchy of a locally refined mesh up
     * to that level, which refine_as() rebuilds on another body of the
     * same scene. Only the levels asked for are gathered: every rank
     * holds the set. */
    std::set<CellId>
    refined_cells(const unsigned int below_level) const;

    /** Refine, up to level @p finest_level, every cell that is in
     * @p refined (another body's refined_cells() of the same scene and
     * coarse mesh): that body's mesh with its cells beyond
     * @p finest_level coarsened (p4est's 2:1 balance may add a few).
     * Quadrilateral meshes only. */
    void
    refine_as(const std::set<CellId> &refined, const unsigned int finest_level);

    /** Replace the mesh by @p mesh (from the remesher), with the scene's
     * manifolds; it becomes the coarse mesh of later uniform refinements.
     * Triangle meshes only. Taken by value: the remesher's mesh is moved
     * in, not copied (a large body's cells each hold their vertices in a
     * vector of their own). */
    void
    replace_mesh(CoarseMeshData mesh);

    /** The scene's coarse mesh of this body, serial, with its boundary ids
     * and manifolds: the geometry a remesher needs. */
    void
    create_scene_coarse_mesh(Triangulation<2> &tria) const;

    /** Distribute DoFs, build constraints and the matrix's sparsity. */
    void
    setup_system();

    /** Assemble stiffness matrix and load vector (tractions, body force). */
    void
    assemble_system();

    /** Set the displacement from the locally owned values @p owned_values
     * (constraints are applied, ghosts updated). */
    void
    set_solution(const TrilinosWrappers::MPI::Vector &owned_values);

    const IndexSet &
    locally_owned_dof_set() const;
    const IndexSet &
    locally_relevant_dof_set() const;

    /** Solve K u = f; the solution satisfies the constraints. */
    LinearSolverReport
    solve(const parameters::LinearSolver &solver_parameters);

    const std::string &
    name() const;
    const BodyDescription &
    description() const;
    const ElasticMaterial &
    material() const;
    const Triangulation<2> &
    triangulation() const;
    const DoFHandler<2> &
    dof_handler() const;
    const Mapping<2> &
    mapping() const;
    const Quadrature<2> &
    cell_quadrature() const;
    const AffineConstraints<double> &
    constraints() const;
    /** The displacement, with ghost entries (locally relevant DoFs). */
    const TrilinosWrappers::MPI::Vector &
    solution() const;
    const TrilinosWrappers::SparseMatrix &
    system_matrix() const;
    const TrilinosWrappers::MPI::Vector &
    system_rhs() const;
    bool
    is_simplex_mesh() const;

    /** The larger side of the body's bounding box over all ranks (mm; a
     * length scale for stresses and loads). Collective. */
    double
    size() const;

    /** Number of vertices of the active mesh over all ranks (hanging
     * vertices included). */
    types::global_dof_index
    n_vertices() const;

    /** True if the Dirichlet data and point constraints cannot hold the
     * body's rigid body motions: without contact its system is singular. */
    bool
    is_floating() const;

    /** The 3 x 3 Gram matrix of the rigid motions (x- and y-translation,
     * rotation about @p centre) restricted to the DoFs that Dirichlet data
     * or point constraints fix, summed over the ranks. Constraints of other
     * kinds (contact) add their own rows; rigid_motion_gram.h says which
     * rigid motions the sum holds. */
    FullMatrix<double>
    support_gram(const Point<2> &centre) const;

    /** Rigid body modes (x-translation, y-translation, rotation about the
     * origin) at the locally owned DoFs: the near null space for AMG.
     * Computed at the first call after setup_system() and kept: an
     * adaptive run asks for them at every load step, equilibrium check
     * and nested level (43 times in the example at 0.25 %), and each
     * computation maps every cell's support points. Not for concurrent
     * calls (the first one fills the cache): the callers are the
     * solvers, on the thread that makes the MPI calls. */
    const std::vector<std::vector<double>> &
    rigid_body_modes() const;

  private:
    void
    create_mesh(const unsigned int n_global_refinements);

    /** create_mesh() through a serial mesh (@p serial holds the scene's
     * coarse mesh): quadrilaterals, and triangles refined uniformly. */
    std::unique_ptr<parallel::TriangulationBase<2>>
    mesh_through_serial_triangulation(Triangulation<2>  &serial,
                                      const unsigned int n_refinements);

    void
    make_constraints();

    MPI_Comm              mpi_communicator;
    const Scene          &scene;
    const unsigned int    body_index;
    const CellType        cell_type;
    const BodyDescription body_description;
    const ElasticMaterial elastic_material;
    bool                  simplex;
    unsigned int          n_global_refinements;
    /** The remesher's mesh, used instead of the scene's coarse mesh. */
    std::optional<CoarseMeshData> remeshed;

    std::unique_ptr<parallel::TriangulationBase<2>> tria;
    std::unique_ptr<FESystem<2>>                    fe;
    std::unique_ptr<Mapping<2>>                     mapping_;
    std::unique_ptr<Quadrature<2>>                  quadrature;
    std::unique_ptr<Quadrature<1>>                  face_quadrature;
    DoFHandler<2>                                   dofs;

    IndexSet locally_owned_dofs;
    IndexSet locally_relevant_dofs;
    /** rigid_body_modes() of the present DoFs (empty: not yet asked). */
    mutable std::vector<std::vector<double>> rigid_modes;
    AffineConstraints<double>                constraints_;
    /** DoFs fixed by Dirichlet data or point constraints. */
    std::set<types::global_dof_index> supported_dofs;
    TrilinosWrappers::SparseMatrix    matrix;
    TrilinosWrappers::MPI::Vector     rhs;
    TrilinosWrappers::MPI::Vector     displacement;
  };
} // namespace coulomb_adapt

#endif
