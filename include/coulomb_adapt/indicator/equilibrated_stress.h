#ifndef coulomb_adapt_indicator_equilibrated_stress_h
#define coulomb_adapt_indicator_equilibrated_stress_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/grid/cell_id.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>

#include <map>
#include <vector>

namespace coulomb_adapt
{
  /** A traction (MPa) prescribed at one point of a cell's boundary, with
   * its quadrature weight (mm): the contact traction of the statically
   * admissible stress, given at the Gauss points of the mortar overlaps. */
  struct BoundaryTractionPoint
  {
    Point<2>     point;
    double       weight;
    Tensor<1, 2> traction;
  };

  /** The traction points of a body's contact boundary, by cell. */
  using ContactTractionData =
    std::map<CellId, std::vector<BoundaryTractionPoint>>;

  /** The volume part of the CRE on one body (theory.md section 7). */
  struct EquilibratedStressErrors
  {
    /** ||sigma^ - sigma_c||^2 on each locally owned active cell (indexed by
     * active cell index; N per unit thickness). */
    Vector<double> error_squared;
    /** sum over all cells of ||sigma^ + sigma_c||^2 (every rank). */
    double sum_norm_squared = 0;
    /** Largest residual of the node systems of the edge moments, relative
     * to the largest element residual: 0 up to round-off when the FE
     * stress is in equilibrium at every free node. */
    double node_system_defect = 0;
    /** Largest load on a rigid motion in the local problems, relative to
     * the load's size: the local problems' data are self-equilibrated to
     * this accuracy. */
    double local_problem_defect = 0;
    /** The largest reaction of a node held by the scene's point
     * constraints that sigma^ does not carry (held_reactions.h), relative
     * to the largest element residual (every rank). */
    double uncarried_held_reaction = 0;
    /** sum over all cells of ||sigma^ - sigma_c||^2 with the edge
     * tractions closest to the averaged traction (before the free
     * parameters are optimised; equal to the sum of error_squared when
     * they are not). */
    double error_squared_before_optimisation = 0;
    /** The number of free parameters optimised, and the truncated CG's
     * steps (0: solved directly). */
    types::global_dof_index optimisation_parameters = 0;
    unsigned int            optimisation_steps      = 0;
    /** Whether the optimisation also moved the relaxed modes (see
     * equilibrated_stress_errors()). */
    bool relaxed = false;
    /** Whether the relaxed system had more parameters than
     * CreMinimisation::exact_up_to and was minimised by the truncated CG
     * instead of exactly. */
    bool exact_minimisation_too_large = false;
    /** Whether the optimised tractions, evaluated with the higher degree
     * of CreMinimisation::evaluation_degree_increase, gave a larger
     * estimate than the classical ones, which were then kept. */
    bool optimisation_kept_classical = false;
  };

  /**
   * How the relaxed system's free parameters are minimised ('Error
   * indicator/CRE minimisation tolerance' and 'CRE exact minimisation up
   * to'). The program and the tests set every member from the parameters
   * (error_estimate.cc), so the defaults that count are the parameters'
   * (core/parameters.cc); those below only keep a default-constructed
   * object defined.
   */
  struct CreMinimisation
  {
    /** 0: exactly, by MUMPS's LDL^T; > 0: by the truncated CG, stopped
     * when its last 10 steps gained less than this fraction of e^2. */
    double tolerance = 0;
    /** With tolerance 0: a body whose system has more parameters than
     * this is minimised by the truncated CG at large_system_tolerance
     * instead; 0: no limit. Why: the factorisation's memory and time grow
     * faster than the mesh (blocks, 420,228 DoFs: 7.9 GB peak, 129 s,
     * against 5.0 GB, 33 s truncated, epsilon 0.1 % higher). */
    types::global_dof_index exact_up_to = 0;
    /** The truncated CG's tolerance above exact_up_to. */
    static constexpr double large_system_tolerance = 1e-3;
    /** > 0: the estimate at the minimum is evaluated with local problems
     * this much higher in degree than the minimisation's (see
     * optimise_free_parameters()). */
    unsigned int evaluation_degree_increase = 0;
    /** Where the body's displacement data are not interpolated exactly:
     * true relaxes the equilibration there too (the estimate then adds
     * the lift of the data's interpolation error, dirichlet_data_lift.h);
     * false keeps the prolongation conditions (parameter 'CRE lift of
     * displacement data'). */
    bool lift_displacement_data = true;
  };

  /**
   * The element equilibration technique of Ladeveze and Leguillon (1983)
   * on @p body, and the CRE's volume terms ||sigma^ - K eps(u_kin)||^2 per
   * cell. @p u_equilibrium (ghosted) must be the FE solution of the body
   * under its own data plus the contact traction @p contact (exactly:
   * its element residuals are what the edge tractions balance);
   * @p u_kinematic (ghosted) is the kinematically admissible field whose
   * error is measured. Conforming meshes only (no hanging nodes).
   *
   * 1. Edge moments b_{G,i} = int_G F_G phi_i: for every node i, the
   *    prolongation conditions of the cells around it,
   *      sum_{G in dE} eta_{E,G} b_{G,i} = int_E sigma : eps(phi_i) - f phi_i,
   *    with the moments known on loaded, free and contact edges and unknown
   *    on interior and Dirichlet edges; solved in least squares closest to
   *    the moments of the averaged traction. The systems of interior and
   *    Dirichlet vertices leave one free parameter per component, and with
   *    @p degree_increase >= 3 each edge with unknown tractions gets a
   *    bubble of degree p + 1 (it changes no moment). With
   *    @p optimise_tractions, these are chosen to minimise the estimate
   *    sum_E ||sigma^ - sigma_c||^2 over all cells (one sparse SPD
   *    system); the classical technique keeps the least-squares choice
   *    (doc/indicator.md compares both). With @p relax_equilibration (and
   *    the bubbles) the optimisation also moves the edge tractions that
   *    keep every cell in equilibrium without the prolongation conditions,
   *    where the body's displacement data are interpolated exactly
   *    (BodyDescription::displacement_data_interpolated_exactly) or
   *    @p minimisation lifts them; that
   *    system is minimised as @p minimisation says (exactly, or by the
   *    truncated CG: 'CRE minimisation tolerance', 'CRE exact minimisation
   *    up to').
   * 2. F_G: the polynomial of degree p on each edge with these moments.
   * 3. On each cell, the Neumann problem with body force f and tractions
   *    eta F_G (the prescribed data on loaded and contact edges) in the
   *    complete polynomials of degree p + @p degree_increase, rigid motions
   *    removed; sigma^ = K eps(u^).
   *
   * With @p timer, the cells' quadratic forms (the local problems and the
   * optimisation's products, with the parameters' matrix built meanwhile)
   * are timed in its section "error indicator: cell forms".
   */
  EquilibratedStressErrors
  equilibrated_stress_errors(const ElasticBody                   &body,
                             const TrilinosWrappers::MPI::Vector &u_equilibrium,
                             const TrilinosWrappers::MPI::Vector &u_kinematic,
                             const ContactTractionData           &contact,
                             const unsigned int     degree_increase,
                             const bool             optimise_tractions,
                             const bool             relax_equilibration,
                             const CreMinimisation &minimisation,
                             TimerOutput           *timer = nullptr);
} // namespace coulomb_adapt

#endif
