#ifndef coulomb_adapt_scenes_scene_h
#define coulomb_adapt_scenes_scene_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/fe/component_mask.h>

#include <deal.II/grid/tria.h>

#include <coulomb_adapt/core/elastic_material.h>
#include <coulomb_adapt/core/parameters.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** Declare the subsections `Body 1` and `Body 2` with their materials,
   * in the current subsection (a scene's). */
  void
  declare_body_materials(ParameterHandler &prm,
                         const double      youngs_modulus_1,
                         const double      poissons_ratio_1,
                         const double      youngs_modulus_2,
                         const double      poissons_ratio_2);

  /** Read the materials declared by declare_body_materials; @p path names
   * the scene's subsection for messages. */
  std::array<MaterialConstants, 2>
  parse_body_materials(ParameterHandler &prm, const std::string &path);

  /** A traction t(x, n) (MPa) on a boundary part, given the outward unit
   * normal n: lets a scene prescribe sigma(x) n from a known stress. */
  using TractionFunction =
    std::function<Tensor<1, 2>(const Point<2> &, const Tensor<1, 2> &)>;

  /** Prescribed displacement (mm) of the components in @p components on
   * the boundary faces with id @p boundary_id. */
  struct DirichletCondition
  {
    types::boundary_id                 boundary_id;
    ComponentMask                      components;
    std::shared_ptr<const Function<2>> displacement;
  };

  /** Zero displacement of the components in @p components at every DoF
   * support point (vertices, and edge nodes for degree 2) for which
   * @p selects is true: point supports and symmetry lines that are not
   * whole boundary parts. */
  struct PointConstraint
  {
    std::function<bool(const Point<2> &)> selects;
    ComponentMask                         components;
    /** When the selected points are a straight segment through the body
     * (a symmetry line), its two end points, which lie on the boundary:
     * remeshing keeps a line of nodes there, without which the
     * constraint would select nothing. */
    std::optional<std::array<Point<2>, 2>> interior_line;
  };

  struct TractionCondition
  {
    types::boundary_id boundary_id;
    TractionFunction   traction;
  };

  /**
   * Everything the solver needs to know about one body besides its mesh.
   */
  struct BodyDescription
  {
    std::string                     name;
    MaterialConstants               material;
    std::vector<DirichletCondition> dirichlet;
    std::vector<PointConstraint>    point_constraints;
    /** The points that point constraints select one by one (point
     * supports): remeshing keeps a node at each. */
    std::vector<Point<2>>          support_points;
    std::vector<TractionCondition> tractions;
    /** Body force per unit volume (N/mm^3); empty means none. */
    std::function<Tensor<1, 2>(const Point<2> &)> body_force;
    /** Boundary id of the candidate contact zone. */
    types::boundary_id contact_boundary_id = numbers::invalid_boundary_id;
    /** The Dirichlet data are polynomials of degree <= 1 (zero, constant,
     * a linearised rotation), which every FE space interpolates exactly,
     * so the FE solution is kinematically admissible: the cre bound
     * assumes it (false for the manufactured scene's sinusoidal data). */
    bool displacement_data_interpolated_exactly = true;
    /** Exact displacement, when the scene knows it (for verification). */
    std::shared_ptr<const Function<2>> exact_displacement;
    /** The boundary parts whose junctions with other parts are singular
     * points of the displacement, where the optimal mesh uses a reduced
     * convergence rate (theory.md section 4). Empty: singular_parts()'s
     * rule. */
    std::vector<types::boundary_id> singular_junction_parts;

    /** singular_junction_parts, or if the scene gives none, the classical
     * corner singularities of mixed boundary conditions: the contact part
     * and every clamped part (all components prescribed). A roller's end
     * is no such point (its mirror image continues the body smoothly). */
    std::vector<types::boundary_id>
    singular_parts() const
    {
      if (!singular_junction_parts.empty())
        return singular_junction_parts;
      std::vector<types::boundary_id> parts;
      if (contact_boundary_id != numbers::invalid_boundary_id)
        parts.push_back(contact_boundary_id);
      for (const auto &condition : dirichlet)
        if (condition.components.n_selected_components(2) == 2)
          parts.push_back(condition.boundary_id);
      return parts;
    }

    /** The interior lines of the point constraints (symmetry lines that
     * a remeshed mesh must keep as lines of nodes). */
    std::vector<std::array<Point<2>, 2>>
    interior_lines() const
    {
      std::vector<std::array<Point<2>, 2>> lines;
      for (const auto &pc : point_constraints)
        if (pc.interior_line)
          lines.push_back(*pc.interior_line);
      return lines;
    }
  };

  /**
   * A scene: the two bodies of a problem, kept out of the solver core (in
   * the manner of ExaDG's applications). Body 0 is the upper, slave body
   * (Omega^1 of theory.md), body 1 the lower, master body (Omega^2).
   */
  class Scene
  {
  public:
    virtual ~Scene() = default;

    virtual std::string
    name() const = 0;

    /** Create the coarse (level-0) mesh of body @p body in @p tria, with
     * boundary ids and manifolds set. @p cell_type is a request: scenes
     * read from files keep the file's cells. */
    virtual void
    create_coarse_mesh(const unsigned int body,
                       const CellType     cell_type,
                       Triangulation<2>  &tria) const = 0;

    /** Local refinement the scene wants before the first solve, applied to
     * quadrilateral meshes before the global refinements (e.g. towards the
     * Hertz contact point). Default: none. */
    virtual void
    refine_initial_mesh(const unsigned int body, Triangulation<2> &tria) const;

    virtual BodyDescription
    describe_body(const unsigned int body) const = 0;

    /** Where the meshes come from, to prefix messages about them ("gmsh
     * file 'x.msh': "). Default: empty, the built-in meshes. */
    virtual std::string
    mesh_source() const;

    /** Analytic reference values the scene knows (e.g. Hertz's a and p0),
     * by name; written to summary.json for plots and comparisons.
     * Default: none. */
    virtual std::map<std::string, double>
    reference_values() const;

    /** The parameter entries that give the scene's loads (full paths, e.g.
     * "Scene/Blocks/Pressure"), for messages about their size. Default:
     * the scene's subsection. */
    virtual std::vector<std::string>
    load_entries() const;

    /** Number of load steps of the scene's quasi-static load path; 1 (the
     * default) is the static problem. */
    virtual unsigned int
    n_load_steps() const;

    /** Put the loads of step @p step (1 ... n_load_steps()) in place: the
     * traction functions of describe_body() follow it. */
    virtual void
    set_load_step(const unsigned int step) const;

    /** The load increment of step @p step (2 ... n_load_steps()) as a
     * multiple of the increment of step @p step - 1, when the two are
     * proportional (the same loads moving on in the same direction): the
     * contact solver then predicts the sets of the step from the last
     * step's increments. 0 (the default) when they are not, or the scene
     * does not say: the step starts from the sets of the step before. */
    virtual double
    load_increment_ratio(const unsigned int step) const;

    /** The same scene with initial meshes @p 2^k times coarser where the
     * scene grades them (towards the contact zone), for nested iteration
     * when the first meshes are not uniform refinements of coarser ones;
     * nullptr (the default) where the scene has no such grading. */
    virtual std::unique_ptr<Scene>
    with_coarser_graded_meshes(const unsigned int k) const;

    /** Whether with_coarser_graded_meshes() scales every mesh size alike
     * (a .geo file meshed at 2^k times its sizes), not only a graded
     * zone: the log names the levels accordingly. */
    virtual bool
    coarser_meshes_scale_every_size() const;
  };
} // namespace coulomb_adapt

#endif
