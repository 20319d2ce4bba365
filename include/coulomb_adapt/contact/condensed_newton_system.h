#ifndef coulomb_adapt_contact_condensed_newton_system_h
#define coulomb_adapt_contact_condensed_newton_system_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/contact/mortar_interface.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  using namespace dealii;

  /**
   * The condensation of the contact multipliers. The dual mortar basis
   * makes D diagonal, so the multiplier of slave node j is explicit,
   *
   *   lambda_j = (f^1 - K^1 u^1)_j / D_jj,
   *
   * and the Newton system has the displacements of both bodies as its
   * only unknowns: one index space with body 2's DoFs shifted by the
   * number of body 1's. This class holds what that needs on every rank:
   * the rows of K^1 and f^1 at the slave DoFs (gathered: the master rows
   * of the system need all of them), and the coupling of master nodes to
   * slave nodes through M. It does not depend on the sets.
   */
  struct SlaveCondensation
  {
    /** A row of K^1 at a slave DoF, with its load. */
    struct SlaveRow
    {
      std::vector<types::global_dof_index> columns;
      std::vector<double>                  values;
      double                               rhs = 0;
    };

    /** Once per mesh and load step (K^1 and f^1 assembled). Checks the
     * Dirichlet data of the covered slave nodes: one Cartesian component
     * along the contact surface may be fixed (a roller: fixed_component),
     * a component along the normal, both, or a hanging-node constraint
     * may not (an error naming the node, on every rank). */
    void
    reinit(const MortarInterface &mortar,
           const ElasticBody     &slave,
           const ElasticBody     &master);

    /** The multipliers lambda_j at every slave node (zero at nodes the
     * master side does not cover) for body 1's displacement @p u1, and
     * a bound on their round-off: (row length + 1) eps sum |terms of
     * f - K u| / D_jj, the same on every rank. */
    struct Multipliers
    {
      std::vector<Tensor<1, 2>> lambda;
      double                    round_off = 0;
    };
    Multipliers
    multipliers(const MortarInterface               &mortar,
                const TrilinosWrappers::MPI::Vector &u1) const;

    MPI_Comm communicator;
    /** n_dofs of body 1: the shift of body 2's indices. */
    types::global_dof_index offset = 0;
    /** Locally owned indices of the combined space. */
    IndexSet owned;
    /** Slave nodes whose rows this rank owns. */
    std::vector<unsigned int>            owned_slave_nodes;
    std::vector<std::array<SlaveRow, 2>> slave_rows;
    /**
     * Slave nodes held along the contact surface (a roller on a symmetry
     * line that meets the surface): the Cartesian component a Dirichlet
     * condition fixes, -1 at free nodes and at nodes the master side
     * does not cover; and the value it fixes. At such a node the
     * Dirichlet condition replaces the tangential contact condition: the
     * multiplier is lambda_n n, lambda_n from the equilibrium of the free
     * component, (f^1 - K^1 u^1)_{j,free} = D_jj lambda_n n_free, and the
     * support carries the tangential reaction (doc/contact.md section 2).
     * The fixed component must lie nearer the tangent than the normal
     * (|n_fixed| < |n_free|), so that n_free is far from zero.
     */
    std::vector<int>    fixed_component;
    std::vector<double> fixed_value;
    /** Per master node and component: whether a Dirichlet condition
     * fixes it, and to which value (on every rank). */
    std::vector<std::array<bool, 2>>   master_fixed;
    std::vector<std::array<double, 2>> master_fixed_value;
    /** D_jj of each slave node. */
    std::vector<double> weights;
    /** For a master DoF: its node and component. */
    std::map<types::global_dof_index, std::pair<unsigned int, unsigned int>>
      master_dof_node;
    /** For a master node: the slave nodes coupled to it with M_jl. */
    std::vector<std::vector<std::pair<unsigned int, double>>> master_to_slave;
  };



  /** One slave node this rank owns, as the current sets see it: what the
   * Newton system of an active-set step needs of it. */
  struct SlaveNodeConditions
  {
    /** Index of the node among the mortar interface's slave nodes. */
    unsigned int index;
    /** Combined indices of the node's x and y displacement. */
    std::array<types::global_dof_index, 2> dofs;
    Tensor<1, 2>                           normal;
    Tensor<1, 2>                           tangent;
    /** D_jj (mm). */
    double weight;
    /** Combined indices of the master DoFs of the coupled master nodes
     * (x and y), with M_jl, and whether that DoF is constrained in body
     * 2 (its row stays K^2's and receives no contact force) and to which
     * value: the Newton solve has zero there (deal.II's constraint rows
     * have a zero right hand side, the value comes with distribute()),
     * so a condition coupled to it takes the value on its right hand
     * side. */
    struct Coupling
    {
      std::array<types::global_dof_index, 2> dofs;
      std::array<bool, 2>                    constrained;
      std::array<double, 2>                  fixed_value;
      double                                 value;
    };
    std::vector<Coupling> couplings;
    /** Normal condition active (the node touches: stick or slip). */
    bool active;
    /** Tangential condition active too (stick). */
    bool stick;
    /** g~_j (mm^2) and, at stick nodes, the weighted slip it keeps. */
    double weighted_gap;
    double weighted_slip;
    /** Direction of the tangential traction at a slip node (+1, -1),
     * and the friction coefficient: the traction lies along
     * n + mu s t. */
    int    slip_sign;
    double friction_coefficient;
    /** The component a roller fixes (SlaveCondensation::fixed_component,
     * -1 if none) and its value: the node's conditions are the normal one
     * and this Dirichlet condition, whatever its set says tangentially. */
    int    fixed_component = -1;
    double fixed_value     = 0;
  };

  /** The conditions of the slave nodes this rank owns, for the sets of
   * @p states. */
  std::vector<SlaveNodeConditions>
  slave_node_conditions(const SlaveCondensation             &condensation,
                        const MortarInterface               &mortar,
                        const std::vector<ContactNodeState> &states,
                        const std::vector<double> &previous_weighted_slip,
                        const double               friction_coefficient);



  /**
   * The Newton system of one active-set step: with the sets fixed the
   * contact conditions are linear (theory.md section 2),
   *
   *   open:  lambda_j = 0
   *   stick: g~_j = 0,  (D u^1 - M u^2)_j . t_j = (its previous value)
   *   slip:  g~_j = 0,  lambda_t,j = mu s_j lambda_n,j,
   *
   * and with the multipliers condensed (SlaveCondensation) the unknowns
   * are the displacements of both bodies. Two forms of the same discrete
   * problem: RowReplacingContactSystem for direct solvers, and
   * EliminatedContactSystem for Krylov + AMG. Their solutions agree to
   * the solvers' accuracy.
   */
  class CondensedNewtonSystem
  {
  public:
    virtual ~CondensedNewtonSystem() = default;

    /** Once per mesh and load step, after SlaveCondensation::reinit:
     * the bodies' systems must be assembled. */
    virtual void
    reinit(const MortarInterface   &mortar,
           const ElasticBody       &slave,
           const ElasticBody       &master,
           const SlaveCondensation &condensation) = 0;

    /** The system for the sets in @p nodes (the slave nodes this rank
     * owns); once per Newton step. */
    virtual void
    assemble(const std::vector<SlaveNodeConditions> &nodes) = 0;

    /** Solve it; @p solution receives u in the combined index space
     * (owned entries). @p near_null_space is used by AMG only. */
    virtual LinearSolverReport
    solve(const std::vector<std::vector<double>> &near_null_space,
          const parameters::LinearSolver         &settings,
          TrilinosWrappers::MPI::Vector          &solution) = 0;
  };
} // namespace coulomb_adapt

#endif
