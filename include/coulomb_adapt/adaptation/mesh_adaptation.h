#ifndef coulomb_adapt_adaptation_mesh_adaptation_h
#define coulomb_adapt_adaptation_mesh_adaptation_h

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /** What one adaptation step did, for the log and summary.json. */
  struct MeshAdaptationReport
  {
    AdaptationStrategy strategy = AdaptationStrategy::uniform;
    /** Predicted cell count N* (both bodies) and epsilon of the optimal
     * mesh, when the size ratios were used; -1 otherwise. */
    double predicted_n_cells = -1;
    double predicted_epsilon = -1;
    /** The epsilon the mesh was planned for (TargetCalibration::aim);
     * -1 when no plan was made. */
    double       aimed_epsilon    = -1;
    unsigned int n_singular_cells = 0;
    unsigned int n_at_min_ratio = 0, n_at_max_ratio = 0;
    /** The lower bound of r_E the plan used ('Minimum size ratio', or its
     * power 3/2 when relaxed; at singular points its power 3/2 again). */
    double min_size_ratio = -1;
    /** When the lower bound was relaxed: what the plan with 'Minimum size
     * ratio' predicted (above the aim); -1 otherwise. */
    double unrelaxed_predicted_epsilon = -1;
    /** Whether the optimal mesh for epsilon_0 exceeded 'Maximum number of
     * DoFs' and the optimal mesh of that size was taken instead. */
    bool limited_by_max_dofs = false;
    /** Whether the optimal mesh for epsilon_0 had fewer cells than
     * 'Minimum number of cells', and the optimal mesh of that many was
     * taken instead. */
    bool limited_by_min_cells = false;
    /** Cells flagged (refine strategy). */
    unsigned int n_refine_flags = 0, n_coarsen_flags = 0;
    /** remesh: how many times each body's gmsh mesh was split into 4
     * (triangle_split.h; 0: gmsh meshed the planned size). */
    std::array<unsigned int, 2> n_triangle_splits = {{0, 0}};
  };

  /**
   * Change both bodies' meshes for the next cycle (theory.md section 4):
   * uniform refinement, hierarchical refinement and coarsening of
   * quadrilaterals, or gmsh remeshing of each body with the optimal size
   * field. @p estimate and @p contact_states are those of the current
   * meshes; the estimate's recovered stresses, which live on these meshes,
   * are released. @p degree is the polynomial degree p. The size-ratio
   * strategies plan the mesh for @p aimed_error, epsilon_0 corrected by
   * what the previous plans achieved (TargetCalibration).
   *
   * The plan bounds r_E below by 'Minimum size ratio' (min_ratio^{3/2} at
   * singular points): the error model, an asymptotic one, is not trusted
   * over more refinement than that in one step from a mesh it has not
   * been checked on. Once @p model_checked (a previous plan's prediction
   * was compared with the mesh it built, and @p aimed_error corrects for
   * the difference), a plan that these bounds keep from its aim is made
   * again with both bounds raised to the power 3/2 (0.1 -> 0.0316, and
   * 0.0316 -> 0.0056 near singular points): otherwise the next mesh
   * misses epsilon_0 by the model alone, and a whole cycle follows (punch,
   * epsilon_0 = 0.25 %: two adaptation steps instead of three, with both
   * strategies; benchmarks/adaptation_steps).
   */
  MeshAdaptationReport
  adapt_meshes(const std::array<ElasticBody *, 2>  &bodies,
               ErrorEstimate                       &estimate,
               const std::vector<ContactNodeState> &contact_states,
               const parameters::Adaptation        &parameters,
               const unsigned int                   degree,
               const double                         aimed_error,
               const bool                           model_checked);
} // namespace coulomb_adapt

#endif
