#include <coulomb_adapt/core/parameter_error.h>
#include <coulomb_adapt/core/parameters.h>

// The subsections of the solvers: 'Linear solver' (the linear systems of
// the bodies and of each Newton step) and 'Contact' (the friction law and
// the semismooth Newton iteration).

namespace coulomb_adapt
{
  namespace parameters
  {
    void
    LinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      {
        prm.declare_entry("Type",
                          "auto",
                          Patterns::Selection(
                            option_pattern<LinearSolverType>()),
                          "direct: sparse direct factorisation (Trilinos "
                          "Amesos). amg: Krylov solver preconditioned by ML "
                          "smoothed-aggregation algebraic multigrid with "
                          "the rigid body modes as near null space: CG for "
                          "elasticity; for contact, the Newton systems with "
                          "the contact conditions eliminated (CG if "
                          "frictionless, GMRES otherwise; doc/contact.md). "
                          "auto: direct up to 'Maximum DoFs for direct' "
                          "(elasticity, per body) or 'Maximum DoFs for "
                          "direct contact' (contact, both bodies), amg "
                          "above.");
        prm.declare_entry("Maximum DoFs for direct",
                          "10000",
                          Patterns::Integer(0),
                          "Largest elastic system (number of DoFs of one "
                          "body) that 'auto' solves directly; CG + AMG "
                          "above. benchmarks/elasticity measured the "
                          "crossover at about 3000 DoFs on 1 rank, and AMG "
                          "4x faster than MUMPS at 1e6 DoFs.");
        prm.declare_entry("Maximum DoFs for direct contact",
                          "5000",
                          Patterns::Integer(0),
                          "Largest contact system (DoFs of both bodies) "
                          "that 'auto' solves directly; Krylov + AMG on the "
                          "eliminated system above. benchmarks/contact "
                          "(README, 'The crossover, measured again') "
                          "measured the crossover of one Newton step at "
                          "about 2e3 DoFs on 1 rank, AMG 1.2-1.8x faster "
                          "from 4e3 to 1e4 DoFs and 1.3-6.7x above. Under "
                          "'auto' a Krylov solve that does not converge "
                          "within 200 iterations (or 'Maximum iterations') "
                          "hands its Newton system, and every later one of "
                          "the run, to the direct solver (the log and "
                          "summary.json say so).");
        prm.declare_entry("Direct solver",
                          "Amesos_Mumps",
                          Patterns::Selection("Amesos_Mumps|Amesos_Klu"),
                          "Amesos package used by the direct solver. "
                          "MUMPS is a parallel multifrontal solver; KLU "
                          "gathers the matrix on one rank and is about 3x "
                          "slower at 5e5 DoFs.");
        prm.declare_entry("Relative tolerance",
                          "1e-10",
                          Patterns::Double(1e-16, 1e-1),
                          "Iterative solver: stop when the residual norm "
                          "has dropped by this factor (dimensionless).");
        prm.declare_entry("Maximum iterations",
                          "1000",
                          Patterns::Integer(1),
                          "Iterative solver: iteration limit; reaching it "
                          "is an error, except for the contact system "
                          "under 'Type = auto', which then goes to the "
                          "direct solver (at most 200 iterations there).");
      }
      prm.leave_subsection();
    }



    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      {
        type                = parse_option<LinearSolverType>(prm.get("Type"));
        max_dofs_for_direct = prm.get_integer("Maximum DoFs for direct");
        max_dofs_for_direct_contact =
          prm.get_integer("Maximum DoFs for direct contact");
        direct_solver      = prm.get("Direct solver");
        relative_tolerance = prm.get_double("Relative tolerance");
        max_iterations     = prm.get_integer("Maximum iterations");
      }
      prm.leave_subsection();
    }



    namespace
    {
      // Where the Newton iteration of a contact solve starts when no
      // previous cycle gives its sets: coarser meshes first (nested
      // iteration), or along a load path the last step's state moved on.
      void
      declare_start_entries(ParameterHandler &prm)
      {
        prm.declare_entry("Nested iteration levels",
                          "3",
                          Patterns::Integer(0),
                          "Contact without a previous cycle's sets: "
                          "solve the same problem first on up to this many "
                          "meshes with fewer uniform refinements (at most "
                          "'Mesh/Global refinements' of them), each starting "
                          "from the sets of the one before, and start the "
                          "Newton iteration from the last one's sets. Where "
                          "that reaches the scene's own meshes, a scene that "
                          "grades them (hertz, cattaneo: a 2, 4, 8 ... times "
                          "coarser contact zone) or meshes a .geo file (its "
                          "'Mesh size factor' times 2, 4, 8 ...) gives this "
                          "many coarser meshes below them. A load path is "
                          "solved on the coarser meshes too, and each of its "
                          "load steps starts from the same step's sets "
                          "there. Fewer Newton steps on the fine mesh "
                          "(hertz, 1.4e5 DoFs: 3 instead of 11; cattaneo's "
                          "tangential steps at 1.4e5 DoFs: at most 4 "
                          "instead of 6); the solution is the same. 0 "
                          "switches it off.");
        prm.declare_entry("Nested iteration minimum DoFs",
                          "0",
                          Patterns::Integer(0),
                          "Nested iteration over global refinements only "
                          "when both bodies together have more DoFs than "
                          "this (0: at every size). Below 2e4 DoFs the "
                          "cold start took up to 9 Newton steps (hertz P1, "
                          "15,742 DoFs; punch P1, 7,764 DoFs: 6) and the "
                          "coarser solves cost less than the steps they "
                          "save. A scene's graded meshes use their coarser "
                          "gradings at every size.");
        prm.declare_entry("Load step predictor",
                          "true",
                          Patterns::Bool(),
                          "On a load path whose scene says that a load step "
                          "moves the loads on as the step before did "
                          "(cattaneo's tangential steps after the first), "
                          "start the step's Newton iteration from the sets "
                          "of the last step's state extrapolated by its "
                          "increments (multipliers, gaps, slips), instead of "
                          "from the last step's sets; if that start stops "
                          "with a diagnosis, the step is solved again from "
                          "the last step's sets. Fewer Newton steps; the "
                          "solution is the same.");
      }
    } // namespace



    void
    Contact::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        prm.declare_entry("Friction coefficient",
                          "0.3",
                          Patterns::Double(),
                          "Coulomb friction coefficient mu >= 0 "
                          "(dimensionless); 0 means frictionless (no "
                          "stick/slip sets).");
        prm.declare_entry(
          "Complementarity scale",
          "1",
          Patterns::Double(0),
          "The constants c_n = c_t of the complementarity "
          "functions are this factor times E_c / h at each "
          "slave node (E_c = E1 E2 / (E1 + E2), h the "
          "node's mortar weight). The converged solution does not "
          "depend on it; it changes the path of the active "
          "set iteration. Must be > 0.");
        prm.declare_entry("Maximum Newton iterations",
                          "40",
                          Patterns::Integer(1),
                          "Semismooth Newton (primal-dual active set) "
                          "iteration limit per start. Reaching it stops the "
                          "solve with a diagnosis; a static solve then starts "
                          "again from the initial gap (after a warm or nested "
                          "start) and with the natural constants (if "
                          "'Complementarity scale' is not 1), and the run "
                          "stops when the last start does.");
        prm.declare_entry("Tolerance",
                          "1e-10",
                          Patterns::Double(0),
                          "Newton has converged when the active, stick and "
                          "slip sets no longer change and the residual of "
                          "the complementarity conditions, relative to the "
                          "largest contact pressure, is below this "
                          "(0 ... 1e-6; 0 accepts the round-off floor "
                          "only). The error indicator's correction treats "
                          "contact reactions that moved by less as "
                          "unchanged (doc/indicator.md section 1).");
        declare_start_entries(prm);
      }
      prm.leave_subsection();
    }



    void
    Contact::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        friction_coefficient    = prm.get_double("Friction coefficient");
        complementarity_scale   = prm.get_double("Complementarity scale");
        max_newton_iterations   = prm.get_integer("Maximum Newton iterations");
        tolerance               = prm.get_double("Tolerance");
        nested_iteration_levels = prm.get_integer("Nested iteration levels");
        nested_iteration_min_dofs =
          prm.get_integer("Nested iteration minimum DoFs");
        load_step_predictor = prm.get_bool("Load step predictor");
        require_parameter(complementarity_scale > 0,
                          "Contact/Complementarity scale",
                          complementarity_scale,
                          "the scale must be > 0");
        // A looser tolerance lets an unconverged iterate pass as converged
        // (1: one Newton step, the sets still changing in the next).
        require_parameter(tolerance >= 0 && tolerance <= 1e-6,
                          "Contact/Tolerance",
                          tolerance,
                          "the relative residual tolerance of the contact "
                          "conditions must be in [0, 1e-6] (default 1e-10); "
                          "a larger one reports an unconverged Newton "
                          "iterate as converged");
        require_parameter(friction_coefficient >= 0,
                          "Contact/Friction coefficient",
                          friction_coefficient,
                          "the friction coefficient must be >= 0");
      }
      prm.leave_subsection();
    }
  } // namespace parameters
} // namespace coulomb_adapt
