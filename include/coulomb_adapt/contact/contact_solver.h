#ifndef coulomb_adapt_contact_contact_solver_h
#define coulomb_adapt_contact_contact_solver_h

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/eliminated_contact_system.h>
#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <array>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  enum class ContactStatus
  {
    open,
    stick,
    slip
  };

  std::string
  to_string(const ContactStatus status);

  /** The contact state at one slave node after the solve. */
  struct ContactNodeState
  {
    Point<2>      position;
    Tensor<1, 2>  normal;
    Tensor<1, 2>  tangent;
    /** Mortar weight D_jj (mm). */
    double        weight;
    /** lambda_n = -R_n >= 0 (MPa). */
    double        pressure;
    /** lambda_t = -R_t (MPa): the traction body 2 receives from body 1
     * along t; body 1 receives its opposite. */
    double        tangential_traction;
    /** Normal gap (mm), >= 0 when open. */
    double        gap;
    /** Tangential jump W_t = (u^1 - u^2) . t (mm). */
    double        slip;
    /** W_t gained in the last load step (mm): the slip of the static
     * problem, the increment of a quasi-static one (the slip of the
     * incremental Coulomb law and of its error indicator). */
    double        slip_increment;
    /** Whether the master surface lies opposite the node (covers its
     * support); if not, the node cannot touch and gap/slip are not
     * defined (reported as 0). */
    bool          facing_master;
    ContactStatus status;
    /** Sign of the slip direction (slip nodes). */
    int           slip_sign;
  };

  /** What a contact solve did, for the log and summary.json. */
  struct ContactSolverReport
  {
    unsigned int        newton_iterations = 0;
    bool                converged         = false;
    unsigned int        n_active = 0, n_stick = 0, n_slip = 0;
    /** Force of body 2 on body 1, sum of D_jj R_j (N/mm). */
    Tensor<1, 2>        contact_force;
    double              max_contact_pressure = 0;
    std::vector<double> residual_history;
    /** Round-off floor of the multipliers at the last Newton step
     * (residual_round_off_floor()); convergence accepts a residual up to
     * max(Contact/Tolerance, this). */
    double              residual_round_off_floor = 0;
    /** Krylov solves repeated with a tighter tolerance because unchanged
     * sets missed Contact/Tolerance (0 or 1). */
    unsigned int        n_tighter_linear_solves = 0;
    bool                frictionless = false;
    /** The converged sets and body 1's Dirichlet data leave its rigid
     * rotation free: its displacement is fixed only up to it. */
    bool                slave_rotation_free = false;
  };

  /**
   * Static two-body Coulomb contact, theory.md section 2: the mortar
   * interface with Wohlmuth's dual multiplier basis, and the semismooth
   * Newton method of Hüeber, Stadler and Wohlmuth in its primal-dual active
   * set form. In 2D, with the sets (open / stick / slip, and the slip
   * direction) fixed, the conditions are linear:
   *
   *   open:  lambda_j = 0
   *   stick: g~_j = 0,  (D u^1 - M u^2)_j . t_j = (its previous value)
   *   slip:  g~_j = 0,  lambda_t,j = mu s_j lambda_n,j
   *
   * and the multipliers are condensed: the dual basis makes D diagonal, so
   * lambda_j = (f^1 - K^1 u^1)_j / D_jj. The unknowns are the displacements
   * of both bodies only; the slave node rows of body 1 are replaced by the
   * conditions of their set and the master rows receive
   * M^T D^-1 (f^1 - K^1 u^1). The system is not symmetric.
   *
   * The sets are updated from the complementarity functions (c_n = c_t =
   * scale E_c / D_jj, E_c = E1 E2 / (E1 + E2)) until they no longer change. mu = 0 takes the
   * frictionless path: active nodes carry no tangential traction, there are
   * no stick or slip sets.
   */
  class ContactSolver
  {
  public:
    ContactSolver(ElasticBody &                   slave,
                  ElasticBody &                   master,
                  const parameters::Contact &     contact_parameters,
                  const parameters::LinearSolver &solver_parameters,
                  const ConditionalOStream &      pcout);

    /** Solve one load step; the bodies' solutions are set. Throws with a
     * diagnosis when the iteration does not converge. The bodies' systems
     * must be assembled (with the loads of this step). Called again for
     * the next load step on the same meshes, it starts from the sets of
     * the previous step, and stick means no slip *in this step*: the
     * quasi-static, incremental form of Coulomb's law. A single call is the
     * static problem of the seed. */
    ContactSolverReport
    solve();

    /** Start the next solve from the sets of @p previous (the node states
     * of a solve on another mesh of the same bodies): each slave node takes
     * the status and slip direction of the nearest previous node. Without
     * it (or if that leaves a floating body 1 without active node) the
     * sets start from the initial gap. */
    void
    warm_start_from(const std::vector<ContactNodeState> &previous);

    /** The last linear solve of the Newton iteration. */
    const LinearSolverReport &
    last_linear_solver_report() const;

    const std::vector<ContactNodeState> &
    node_states() const;

    const MortarInterface &
    mortar_interface() const;

  private:
    /** A row of K^1 at a slave DoF, with its load. */
    struct SlaveRow
    {
      std::vector<types::global_dof_index> columns;
      std::vector<double>                  values;
      double                               rhs = 0;
    };

    void
    setup();
    void
    build_row_replacing_pattern();
    /** The slave nodes this rank owns, with their current conditions, for
     * EliminatedContactSystem. */
    std::vector<EliminatedContactSystem::SlaveNode>
    eliminated_slave_nodes() const;
    void
    initialize_sets();
    void
    transfer_warm_start_sets();
    void
    check_support(const unsigned int step) const;
    /** Whether the current sets and body 1's Dirichlet data leave a rigid
     * rotation of body 1 free (the Newton system is then singular). */
    bool
    slave_rotation_free() const;
    std::vector<std::vector<double>>
    rigid_body_modes() const;
    /** E1 E2 / (E1 + E2): the modulus that scales c and the residual. */
    double
    combined_modulus() const;
    void
    assemble_newton_system();
    void
    solve_newton_system();
    void
    evaluate_contact_state();
    unsigned int
    update_sets();
    double
    complementarity_residual() const;
    /** The largest contact pressure (1 if there is none). */
    double
    largest_pressure() const;
    /** Node j's term of the complementarity residual, normalised by the
     * largest pressure @p p. */
    double
    node_residual(const unsigned int j, const double p) const;
    /** Restricted set update: of the nodes whose sets changed from
     * @p before, only those whose residual is at least @p fraction of
     * the largest keep the change; the others return to @p before.
     * Returns the number of nodes that keep their change. */
    unsigned int
    restrict_set_changes(const std::vector<ContactNodeState> &before,
                         const double                         fraction);
    /** If the sets hold no stick node and nothing else holds body 1
     * tangentially (mu > 0), put the active node whose trial traction lies
     * deepest inside the Coulomb cone into stick. Returns that node, or
     * states.size() if nothing was done. */
    unsigned int
    keep_one_node_stuck();
    std::string
    set_signature() const;
    /** The complementarity residual that round-off alone can leave:
     * multiplier_round_off / (largest pressure). */
    double
    residual_round_off_floor() const;
    /** Tangential slip of node j in the current load step (mm). */
    double
    slip_increment(const unsigned int j) const;
    /** The arguments of the complementarity functions of theory.md
     * section 2 at node j for the constant c: lambda_n - c g_j and the
     * trial traction lambda_t + c dW_t,j. */
    struct TrialTractions
    {
      double normal;
      double tangential;
    };
    TrialTractions
    trial_tractions(const unsigned int j, const double c) const;
    /** The unit mean tangent of the slave nodes that face the master
     * side (zero if none does): the direction in which body 1 slides. */
    Tensor<1, 2>
    interface_tangent() const;
    /** The natural constant E_c / D_jj of node j, independent of
     * 'Contact/Complementarity scale'. */
    double
    natural_constant(const unsigned int j) const;

    ElasticBody &                    slave;
    ElasticBody &                    master;
    const parameters::Contact        contact_parameters;
    const parameters::LinearSolver   solver_parameters;
    const ConditionalOStream &       pcout;
    const MPI_Comm                   mpi_communicator;
    const double                     mu;

    MortarInterface                  mortar;
    types::global_dof_index          offset; // n_dofs of body 1
    IndexSet                         owned;
    std::vector<std::array<SlaveRow, 2>> slave_rows;
    /** Slave nodes whose rows this rank owns. */
    std::vector<unsigned int>        owned_slave_nodes;
    /** For a master DoF: its node and component. */
    std::map<types::global_dof_index, std::pair<unsigned int, unsigned int>>
                                     master_dof_node;
    /** For a master node: the slave nodes coupled to it with M_jl. */
    std::vector<std::vector<std::pair<unsigned int, double>>> master_to_slave;
    std::vector<double>              complementarity_constant;
    /** Bound on the round-off of the nodal multipliers at the last
     * evaluation (MPa): (row length + 1) eps sum |terms of f - K u| / D. */
    double                           multiplier_round_off = 0;
    double                           row_scale;

    /** Krylov + AMG: the Newton systems are solved with the contact
     * conditions eliminated (direct solves take the row-replacing
     * matrix below). Decided in setup() from 'Linear solver/Type'. */
    bool                             iterative = false;
    EliminatedContactSystem          eliminated_system;
    TrilinosWrappers::SparseMatrix   matrix;
    LinearSolverReport               last_linear_solve;
    /** rigid_body_modes() of this load step, for the AMG path; empty for
     * direct solves. */
    std::vector<std::vector<double>> near_null_space;
    /** Body 1's supported rigid motions (ElasticBody::support_gram) about
     * support_centre, the mean slave node position; once per load step
     * (setup()), for all support tests of the Newton steps. */
    FullMatrix<double>               slave_support_gram;
    Point<2>                         support_centre;
    /** Factor on the Krylov tolerance: 1, and 1e-2 when unchanged
     * sets miss the complementarity tolerance (ContactSolver::solve). */
    double linear_tolerance_factor = 1;
    TrilinosWrappers::MPI::Vector    rhs;

    std::vector<ContactNodeState>    states;
    /** States of a previous mesh to start from (warm_start_from). */
    std::vector<ContactNodeState>    warm_start_states;
    /** Weighted tangential jump at the end of the previous load step. */
    std::vector<double>              previous_weighted_slip;
  };
} // namespace coulomb_adapt

#endif
