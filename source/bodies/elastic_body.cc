#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/manifold_mapping_fe.h>
#include <coulomb_adapt/bodies/rigid_motion_gram.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace coulomb_adapt
{
  ElasticBody::ElasticBody(const MPI_Comm                    mpi_communicator,
                           const Scene                      &scene,
                           const unsigned int                body_index,
                           const CellType                    cell_type,
                           const unsigned int                global_refinements,
                           const parameters::FiniteElements &fe_parameters)
    : mpi_communicator(mpi_communicator)
    , scene(scene)
    , body_index(body_index)
    , cell_type(cell_type)
    , body_description(scene.describe_body(body_index))
    , elastic_material(body_description.material, fe_parameters.plane_model)
    , simplex(false)
    , n_global_refinements(global_refinements)
  {
    create_mesh(n_global_refinements);

    const unsigned int p = fe_parameters.degree;
    if (simplex)
      {
        // On curved boundaries (a manifold other than the flat one) the
        // mapping has the element's degree and puts the edge nodes on the
        // curve; on straight-sided meshes it would give the same affine
        // cells at more cost.
        bool curved = false;
        for (const auto id : tria->get_manifold_ids())
          curved = curved || id != numbers::flat_manifold_id;
        fe = std::make_unique<FESystem<2>>(FE_SimplexP<2>(p), 2);
        if (curved && p > 1)
          mapping_ = std::make_unique<ManifoldMappingFE>(FE_SimplexP<2>(p));
        else
          mapping_ = std::make_unique<MappingFE<2>>(FE_SimplexP<2>(1));
        quadrature = std::make_unique<QGaussSimplex<2>>(p + 1);
      }
    else
      {
        fe         = std::make_unique<FESystem<2>>(FE_Q<2>(p), 2);
        mapping_   = std::make_unique<MappingQ<2>>(p);
        quadrature = std::make_unique<QGauss<2>>(p + 1);
      }
    face_quadrature = std::make_unique<QGauss<1>>(p + 1);
  }



  ElasticBody::~ElasticBody()
  {
    dofs.clear();
  }



  void
  ElasticBody::setup_system()
  {
    dofs.distribute_dofs(*fe);
    locally_owned_dofs = dofs.locally_owned_dofs();
    rigid_modes.clear();
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);

    make_constraints();

    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dofs, dsp, constraints_, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               locally_owned_dofs,
                                               mpi_communicator,
                                               locally_relevant_dofs);
    matrix.reinit(locally_owned_dofs,
                  locally_owned_dofs,
                  dsp,
                  mpi_communicator);
    rhs.reinit(locally_owned_dofs, mpi_communicator);
    displacement.reinit(locally_owned_dofs,
                        locally_relevant_dofs,
                        mpi_communicator);
  }



  void
  ElasticBody::make_constraints()
  {
    constraints_.clear();
    constraints_.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints_);

    supported_dofs.clear();
    for (const auto &d : body_description.dirichlet)
      {
        VectorTools::interpolate_boundary_values(*mapping_,
                                                 dofs,
                                                 d.boundary_id,
                                                 *d.displacement,
                                                 constraints_,
                                                 d.components);
        const IndexSet on_boundary =
          DoFTools::extract_boundary_dofs(dofs, d.components, {d.boundary_id});
        for (const auto i : on_boundary)
          supported_dofs.insert(i);
      }

    // Point constraints act on every DoF whose support point they select
    // (vertices and, for degree 2, edge and cell nodes).
    if (!body_description.point_constraints.empty())
      {
        const Quadrature<2> support_points(fe->get_unit_support_points());
        FEValues<2>         fe_values(*mapping_,
                              *fe,
                              support_points,
                              update_quadrature_points);
        std::vector<types::global_dof_index> local_dof_indices(
          fe->n_dofs_per_cell());
        const auto &point_constraints = body_description.point_constraints;
        std::vector<unsigned int> n_selected(point_constraints.size(), 0);
        for (const auto &cell : dofs.active_cell_iterators())
          if (!cell->is_artificial())
            {
              fe_values.reinit(cell);
              cell->get_dof_indices(local_dof_indices);
              for (unsigned int i = 0; i < local_dof_indices.size(); ++i)
                for (unsigned int p = 0; p < point_constraints.size(); ++p)
                  if (point_constraints[p]
                        .components[fe->system_to_component_index(i).first] &&
                      point_constraints[p].selects(
                        fe_values.quadrature_point(i)))
                    {
                      ++n_selected[p];
                      const auto dof = local_dof_indices[i];
                      supported_dofs.insert(dof);
                      if (!constraints_.is_constrained(dof))
                        constraints_.add_line(dof);
                    }
            }
        // A support that selects no node would leave the body silently
        // free (the hertz disc's axis on a mesh without nodes there let
        // the stability sweep's case 286 float).
        Utilities::MPI::sum(n_selected, mpi_communicator, n_selected);
        for (unsigned int p = 0; p < point_constraints.size(); ++p)
          AssertThrow(n_selected[p] > 0,
                      ExcMessage(
                        "body '" + body_description.name +
                        "': its point support or symmetry line (the "
                        "scene's hold option) selects no node of this mesh: "
                        "the mesh has no nodes there. Mesh files must put "
                        "nodes on it, or turn the hold option off."));
      }
    constraints_.close();
  }



  namespace
  {
    // The stiffness 2 mu eps(u):eps(v) + lambda div u div v and the body
    // force of one cell; the lower triangle is summed, then mirrored.
    // @p strain and @p divergence are scratch space (one entry per DoF).
    void
    add_cell_terms(const FEValues<2>                  &fe_values,
                   const double                        lambda,
                   const double                        mu,
                   const BodyDescription              &description,
                   std::vector<SymmetricTensor<2, 2>> &strain,
                   std::vector<double>                &divergence,
                   FullMatrix<double>                 &cell_matrix,
                   Vector<double>                     &cell_rhs)
    {
      const FEValuesExtractors::Vector displacement_view(0);
      const auto                      &fv = fe_values[displacement_view];
      const unsigned int               dofs_per_cell = cell_rhs.size();
      for (const unsigned int q : fe_values.quadrature_point_indices())
        {
          const double JxW = fe_values.JxW(q);
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              strain[i]     = fv.symmetric_gradient(i, q);
              divergence[i] = trace(strain[i]);
            }
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            for (unsigned int j = 0; j <= i; ++j)
              cell_matrix(i, j) += (2. * mu * (strain[i] * strain[j]) +
                                    lambda * divergence[i] * divergence[j]) *
                                   JxW;
          if (description.body_force)
            {
              const Tensor<1, 2> f =
                description.body_force(fe_values.quadrature_point(q));
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                cell_rhs(i) += fv.value(i, q) * f * JxW;
            }
        }
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
          cell_matrix(i, j) = cell_matrix(j, i);
    }



    // The tractions on the cell's boundary faces that carry one.
    void
    add_traction_terms(
      const DoFHandler<2>::active_cell_iterator                    &cell,
      const std::map<types::boundary_id, const TractionFunction *> &traction_on,
      FEFaceValues<2> &fe_face_values,
      Vector<double>  &cell_rhs)
    {
      const FEValuesExtractors::Vector displacement_view(0);
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            const auto t = traction_on.find(face->boundary_id());
            if (t == traction_on.end())
              continue;
            fe_face_values.reinit(cell, face);
            const auto &ffv = fe_face_values[displacement_view];
            for (const unsigned int q :
                 fe_face_values.quadrature_point_indices())
              {
                const Tensor<1, 2> traction =
                  (*t->second)(fe_face_values.quadrature_point(q),
                               fe_face_values.normal_vector(q));
                for (unsigned int i = 0; i < cell_rhs.size(); ++i)
                  cell_rhs(i) +=
                    ffv.value(i, q) * traction * fe_face_values.JxW(q);
              }
          }
    }
  } // namespace



  void
  ElasticBody::assemble_system()
  {
    matrix = 0;
    rhs    = 0;

    // Scratch of one thread: the FEValues and the strains of one cell.
    struct Scratch
    {
      Scratch(const Mapping<2>       &mapping,
              const FiniteElement<2> &fe,
              const Quadrature<2>    &quadrature,
              const Quadrature<1>    &face_quadrature)
        : fe_values(mapping,
                    fe,
                    quadrature,
                    update_values | update_gradients |
                      update_quadrature_points | update_JxW_values)
        , fe_face_values(mapping,
                         fe,
                         face_quadrature,
                         update_values | update_quadrature_points |
                           update_normal_vectors | update_JxW_values)
        , strain(fe.n_dofs_per_cell())
        , divergence(fe.n_dofs_per_cell())
      {}

      Scratch(const Scratch &other)
        : Scratch(other.fe_values.get_mapping(),
                  other.fe_values.get_fe(),
                  other.fe_values.get_quadrature(),
                  other.fe_face_values.get_quadrature())
      {}

      FEValues<2>                        fe_values;
      FEFaceValues<2>                    fe_face_values;
      std::vector<SymmetricTensor<2, 2>> strain;
      std::vector<double>                divergence;
    };
    // What one cell adds to the matrix and the load.
    struct Copy
    {
      FullMatrix<double>                   cell_matrix;
      Vector<double>                       cell_rhs;
      std::vector<types::global_dof_index> local_dof_indices;
    };

    std::map<types::boundary_id, const TractionFunction *> traction_on;
    for (const auto &t : body_description.tractions)
      traction_on[t.boundary_id] = &t.traction;

    // The cells are independent until they are added: WorkStream computes
    // them on the threads deal.II may use and adds them in the cells'
    // order, so the matrix and the load agree to round-off on any number
    // of threads (FEValues reuses the geometry of a translated previous
    // cell, and each thread has its own previous cell).
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    using OwnedCell = FilteredIterator<DoFHandler<2>::active_cell_iterator>;
    WorkStream::run(
      OwnedCell(IteratorFilters::LocallyOwnedCell(), dofs.begin_active()),
      OwnedCell(IteratorFilters::LocallyOwnedCell(), dofs.end()),
      [&](const OwnedCell &cell, Scratch &scratch, Copy &copy) {
        copy.cell_matrix.reinit(dofs_per_cell, dofs_per_cell);
        copy.cell_rhs.reinit(dofs_per_cell);
        copy.local_dof_indices.resize(dofs_per_cell);
        scratch.fe_values.reinit(cell);
        add_cell_terms(scratch.fe_values,
                       elastic_material.lambda(),
                       elastic_material.mu(),
                       body_description,
                       scratch.strain,
                       scratch.divergence,
                       copy.cell_matrix,
                       copy.cell_rhs);
        add_traction_terms(cell,
                           traction_on,
                           scratch.fe_face_values,
                           copy.cell_rhs);
        cell->get_dof_indices(copy.local_dof_indices);
      },
      [&](const Copy &copy) {
        constraints_.distribute_local_to_global(
          copy.cell_matrix, copy.cell_rhs, copy.local_dof_indices, matrix, rhs);
      },
      Scratch(*mapping_, *fe, *quadrature, *face_quadrature),
      Copy());
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }



  LinearSolverReport
  ElasticBody::solve(const parameters::LinearSolver &solver_parameters)
  {
    TrilinosWrappers::MPI::Vector owned(locally_owned_dofs, mpi_communicator);
    LinearSolverReport            report;
    try
      {
        report = solve_linear_system(
          matrix, owned, rhs, rigid_body_modes(), solver_parameters);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        // deal.II's text names neither the body nor the parameter.
        AssertThrow(false,
                    ExcMessage(iteration_limit_message("body '" + name() + "'",
                                                       "CG + AMG",
                                                       e.last_step,
                                                       e.last_residual)));
      }
    constraints_.distribute(owned);
    displacement = owned;
    return report;
  }



  void
  ElasticBody::set_solution(const TrilinosWrappers::MPI::Vector &owned_values)
  {
    TrilinosWrappers::MPI::Vector owned(owned_values);
    constraints_.distribute(owned);
    displacement = owned;
  }



  const IndexSet &
  ElasticBody::locally_owned_dof_set() const
  {
    return locally_owned_dofs;
  }



  const IndexSet &
  ElasticBody::locally_relevant_dof_set() const
  {
    return locally_relevant_dofs;
  }



  const std::vector<std::vector<double>> &
  ElasticBody::rigid_body_modes() const
  {
    if (!rigid_modes.empty())
      return rigid_modes;
    const unsigned int               n_local = locally_owned_dofs.n_elements();
    std::vector<std::vector<double>> modes(3, std::vector<double>(n_local));

    const Quadrature<2> support_points(fe->get_unit_support_points());
    FEValues<2>         fe_values(*mapping_,
                          *fe,
                          support_points,
                          update_quadrature_points);
    std::vector<types::global_dof_index> local_dof_indices(
      fe->n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(local_dof_indices);
          for (unsigned int i = 0; i < local_dof_indices.size(); ++i)
            if (locally_owned_dofs.is_element(local_dof_indices[i]))
              {
                const unsigned int k =
                  locally_owned_dofs.index_within_set(local_dof_indices[i]);
                const unsigned int c = fe->system_to_component_index(i).first;
                const Point<2>    &x = fe_values.quadrature_point(i);
                modes[0][k]          = (c == 0) ? 1. : 0.;
                modes[1][k]          = (c == 1) ? 1. : 0.;
                modes[2][k]          = (c == 0) ? -x[1] : x[0];
              }
        }
    rigid_modes = std::move(modes);
    return rigid_modes;
  }



  // A body is held if the rigid modes restricted to the supported DoFs are
  // linearly independent: their 3 x 3 Gram matrix is regular.
  bool
  ElasticBody::is_floating() const
  {
    return !holds_all_rigid_motions(support_gram(Point<2>()));
  }



  FullMatrix<double>
  ElasticBody::support_gram(const Point<2> &centre) const
  {
    // The rows are the rigid modes (rotation about the origin) at the
    // supported DoFs.
    const auto        &modes = rigid_body_modes();
    FullMatrix<double> gram(3, 3);
    for (const auto dof : supported_dofs)
      if (locally_owned_dofs.is_element(dof))
        {
          const unsigned int k = locally_owned_dofs.index_within_set(dof);
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              gram(a, b) += modes[a][k] * modes[b][k];
        }
    Utilities::MPI::sum(gram, mpi_communicator, gram);
    return move_rotation_centre(gram, centre - Point<2>());
  }



  const std::string &
  ElasticBody::name() const
  {
    return body_description.name;
  }
  const BodyDescription &
  ElasticBody::description() const
  {
    return body_description;
  }
  const ElasticMaterial &
  ElasticBody::material() const
  {
    return elastic_material;
  }
  const Triangulation<2> &
  ElasticBody::triangulation() const
  {
    return *tria;
  }
  const DoFHandler<2> &
  ElasticBody::dof_handler() const
  {
    return dofs;
  }
  const Mapping<2> &
  ElasticBody::mapping() const
  {
    return *mapping_;
  }
  const Quadrature<2> &
  ElasticBody::cell_quadrature() const
  {
    return *quadrature;
  }
  const AffineConstraints<double> &
  ElasticBody::constraints() const
  {
    return constraints_;
  }
  const TrilinosWrappers::MPI::Vector &
  ElasticBody::solution() const
  {
    return displacement;
  }
  const TrilinosWrappers::SparseMatrix &
  ElasticBody::system_matrix() const
  {
    return matrix;
  }
  const TrilinosWrappers::MPI::Vector &
  ElasticBody::system_rhs() const
  {
    return rhs;
  }
  // The vertices of the active mesh are the DoFs of a scalar linear
  // element on it, which the DoFHandler counts across ranks for us.
  types::global_dof_index
  ElasticBody::n_vertices() const
  {
    DoFHandler<2> vertex_dofs(*tria);
    if (simplex)
      vertex_dofs.distribute_dofs(FE_SimplexP<2>(1));
    else
      vertex_dofs.distribute_dofs(FE_Q<2>(1));
    return vertex_dofs.n_dofs();
  }



  bool
  ElasticBody::is_simplex_mesh() const
  {
    return simplex;
  }



  double
  ElasticBody::size() const
  {
    // By hand rather than GridTools::compute_bounding_box(), which needs a
    // locally owned cell on every rank.
    std::array<double, 2> lower = {
      {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}};
    std::array<double, 2> upper = {{-lower[0], -lower[1]}};
    for (const auto &cell : triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 2; ++d)
            {
              lower[d] = std::min(lower[d], cell->vertex(v)[d]);
              upper[d] = std::max(upper[d], cell->vertex(v)[d]);
            }
    const MPI_Comm comm = triangulation().get_communicator();
    double         size = 0;
    for (unsigned int d = 0; d < 2; ++d)
      size = std::max(size,
                      Utilities::MPI::max(upper[d], comm) -
                        Utilities::MPI::min(lower[d], comm));
    return size;
  }
} // namespace coulomb_adapt
