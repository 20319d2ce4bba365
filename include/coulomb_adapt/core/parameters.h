#ifndef coulomb_adapt_core_parameters_h
#define coulomb_adapt_core_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <coulomb_adapt/core/error_estimator.h>
#include <coulomb_adapt/core/options.h>

#include <string>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The parameters of the program, one struct per subsection of the
   * parameter file (in the style of Lethe's `parameters.h`). Subsection
   * `Scene` lives with the scenes, which the parameters here know nothing
   * of (scenes/scene_factory.h declares it and reads it).
   */
  namespace parameters
  {
    /** Subsection `Output`. */
    struct Output
    {
      std::string  directory;
      OutputFormat format;
      WriteCycles  write_cycles;
      unsigned int cells_per_vtu_piece;
      bool         write_in_background;
      bool         write_smoothed_stress;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Mesh`. */
    struct Mesh
    {
      CellType     cell_type;
      unsigned int global_refinements;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Finite elements`. */
    struct FiniteElements
    {
      unsigned int degree;
      PlaneModel   plane_model;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Linear solver`. */
    struct LinearSolver
    {
      LinearSolverType type;
      unsigned int     max_dofs_for_direct;
      std::string      direct_solver;
      double           relative_tolerance;
      unsigned int     max_iterations;
      /** 'Maximum DoFs for direct' for the contact system (DoFs of both
       * bodies). */
      unsigned int max_dofs_for_direct_contact;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Contact`. */
    struct Contact
    {
      double friction_coefficient;
      /** c_n = c_t = scale * E / h at each slave node (dimensionless). */
      double       complementarity_scale;
      unsigned int max_newton_iterations;
      /** Relative residual of the complementarity functions. */
      double tolerance;
      /** Coarser meshes solved first for the initial sets (0: none). */
      unsigned int nested_iteration_levels;
      /** Nested iteration only for problems with more DoFs than this. */
      unsigned int nested_iteration_min_dofs;
      /** Later load steps of a proportional load path start from sets
       * extrapolated from the last step's increments. */
      bool load_step_predictor;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Error indicator`. */
    struct ErrorIndicator
    {
      /** The estimator that drives the adaptation. */
      ErrorEstimator estimator;
      /** Compute all estimators on the same solution every cycle. */
      bool compare_estimators;
      /** k of the cre estimator's local problems (degree p + k). */
      unsigned int cre_degree_increase;
      /** The optimised estimate is evaluated with local problems of
       * degree p + k + this (0: those of the minimisation). */
      unsigned int cre_evaluation_degree_increase;
      /** Choose the equilibration's free parameters to minimise the cre
       * estimate (else: closest to the averaged traction). */
      bool cre_traction_optimisation;
      bool cre_relaxed_equilibration;
      /** Where the displacement data are not interpolated exactly: relax
       * the equilibration there too, and add the lift of the data's
       * interpolation error to the bound (dirichlet_data_lift.h). */
      bool cre_lift_displacement_data;
      /** With the relaxed equilibration: 0 minimises the estimate exactly
       * (sparse direct solve); > 0 stops the truncated CG when the
       * estimate's last steps gain less than this fraction of it. */
      double cre_minimisation_tolerance;
      /** With tolerance 0: the most parameters a body's system may have
       * for the exact minimisation (above: the truncated CG at 1e-3);
       * 0: no limit. */
      types::global_dof_index cre_exact_minimisation_up_to;
      /** Compare with the exact error: the scene's exact solution if it
       * has one, else a reference solution on a finer mesh. */
      bool compute_exact_error;
      /** Uniform refinements of the reference mesh beyond the current one. */
      unsigned int reference_refinements;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Adaptation`. */
    struct Adaptation
    {
      /** uniform: every cycle refines all cells once; refine:
       * quadrilaterals refined and coarsened with hanging nodes; remesh:
       * each body remeshed by gmsh from the optimal size field. */
      AdaptationStrategy strategy;
      /** Maximum number of solve cycles. */
      unsigned int n_cycles;
      /** Cycles run even if the target is met earlier. */
      unsigned int min_cycles;
      /** remesh: below this fraction of epsilon_0 a mesh is optimised
       * again rather than accepted (0: never). */
      double over_refinement_ratio;
      /** epsilon_0 as a fraction (the file gives percent); 0: no target. */
      double target_error;
      /** The optimal mesh is planned for this fraction of epsilon_0
       * (times the correction measured on the previous plans). */
      double target_safety_factor;
      /** No further cycle once a cycle has at least this many DoFs. */
      double max_dofs;
      /** The size-ratio plans build no mesh of fewer cells (both bodies). */
      double min_cells;
      /** Which cells the strategy 'refine' flags. */
      RefinementCriterion refinement_criterion;
      double              refine_fraction;
      double              coarsen_fraction;
      /** Bounds of r_E = h*_E / h_E. */
      double min_size_ratio;
      double max_size_ratio;
      /** Local convergence rate q used in cells at singular points. */
      double singular_rate;
      /** Start Newton from the previous cycle's contact sets. */
      bool warm_start;
      /** A cycle with at least this many times the previous cycle's DoFs
       * starts from nested iteration on the scene's uniform refinements
       * instead (0: always the warm start). */
      double nested_start_dof_ratio;
      /** gmsh's 2D algorithm for remesh. */
      RemeshingAlgorithm remeshing_algorithm =
        RemeshingAlgorithm::frontal_delaunay;
      /** remesh: a body planned for more cells than this is meshed by gmsh
       * 2^k times coarser and split k times (red refinement); 0: never. */
      unsigned int remeshing_split_above_cells = 0;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace parameters

  /**
   * All parameters of a run but the scene's. The ParameterHandler is kept
   * because the scenes read subsection `Scene` from it, and because every
   * run writes the resolved parameter set next to its results.
   */
  struct Parameters
  {
    parameters::Mesh           mesh;
    parameters::FiniteElements finite_elements;
    parameters::Contact        contact;
    parameters::LinearSolver   linear_solver;
    parameters::ErrorIndicator error_indicator;
    parameters::Adaptation     adaptation;
    parameters::Output         output;

    /** Declare every entry of these subsections (the program's whole set
     * is TwoBodyProblem::declare_parameters). */
    static void
    declare_parameters(ParameterHandler &prm);
    /** Read and check every entry; throws ParameterError on bad values. */
    void
    parse_parameters(ParameterHandler &prm);
  };
} // namespace coulomb_adapt

#endif
