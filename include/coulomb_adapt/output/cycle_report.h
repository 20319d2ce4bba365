#ifndef coulomb_adapt_output_cycle_report_h
#define coulomb_adapt_output_cycle_report_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/table_handler.h>
#include <deal.II/base/timer.h>

#include <coulomb_adapt/adaptation/mesh_adaptation.h>
#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/bodies/elasticity_errors.h>
#include <coulomb_adapt/contact/contact_solve_driver.h>
#include <coulomb_adapt/core/parameters.h>
#include <coulomb_adapt/core/units.h>
#include <coulomb_adapt/indicator/error_estimate.h>
#include <coulomb_adapt/indicator/exact_error.h>
#include <coulomb_adapt/output/run_summary.h>
#include <coulomb_adapt/solvers/linear_solver.h>

#include <nlohmann/json.hpp>

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace coulomb_adapt
{
  /**
   * What the program tells about its cycles: the log lines a user watches
   * (on rank 0) and the machine-readable record of each cycle in
   * summary.json (RunSummary), from the same numbers, and the table of all
   * cycles at the end. The program hands it the reports of its phases as
   * they finish; each record_*() writes the phase's log lines and its
   * entries of the cycle's record.
   */
  class CycleReport
  {
  public:
    /** @p timer is the program's: its sections' wall times go into each
     * cycle's record. */
    CycleReport(const MPI_Comm            mpi_communicator,
                const ConditionalOStream &pcout,
                const TimerOutput        &timer,
                const std::string        &summary_file,
                const std::string        &scene,
                const std::string        &parameter_file);

    /** A top-level entry of summary.json (not per cycle). */
    void
    set_run_entry(const std::string &key, const nlohmann::json &value);

    /** The load scale P of the run (core/units.h), written to summary.json
     * as "load_scale": from now on the numbers of the scaled problem
     * handed in are reported multiplied by P (displacements, stresses,
     * forces) or P^2 (energies), where that is a finite normal double;
     * otherwise as given, their keys listed under "reported_scaled" and
     * said so in the log. */
    void
    set_load_scale(const double load_scale);

    /** The same with a displacement scale D other than P (extreme moduli
     * or an initial gap, core/units.h): "load_scale" P and "displacement_scale"
     * D in summary.json; displacements, gaps and slips are reported
     * multiplied by D, stresses and forces by P, energies by P D. */
    void
    set_scales(const units::Scales &scales);

    /** @p scaled (of the scaled problem, a quantity of kind @p kind:
     * units::Kind) as a physical value, or as given if that is not
     * representable (then @p key is listed as reported scaled). */
    double
    physical(const double       scaled,
             const units::Kind  kind,
             const std::string &key);

    /** Record that @p key is reported in the scaled form (once: a log
     * line with @p reason, and the key under "reported_scaled"). */
    void
    report_scaled(const std::string &key, const std::string &reason);

    /** Start the record and the clock of cycle @p cycle. */
    void
    begin_cycle(const unsigned int cycle);

    /** The adaptation that makes the meshes of this cycle (logged when it
     * is done, recorded with the meshes it made). */
    void
    record_mesh_adaptation(const MeshAdaptationReport   &report,
                           const parameters::Adaptation &parameters,
                           const unsigned int            degree,
                           const double                  calibration);

    /** The meshes of this cycle; @p last_adaptation the adaptation that
     * made them (null on the first cycle). */
    void
    record_meshes(const std::array<const ElasticBody *, 2> &bodies,
                  const AdaptationStrategy                  strategy,
                  const MeshAdaptationReport               *last_adaptation,
                  const double                              calibration);

    /** Both bodies' DoFs in this cycle (after record_meshes()). */
    types::global_dof_index
    n_dofs() const;

    /** This cycle's exact error of the driving estimate, where it was
     * computed: extrapolated over the reference's levels where they
     * allowed it (record_reference_solution), else against the reference
     * or the exact solution. */
    std::optional<double>
    exact_error() const;

    /** For an estimate that claims to bound the error (target_claim.h),
     * @p estimate against this cycle's exact error (exact_error()):
     * summary.json "bound_holds", and a warning in the log where it is
     * below. The exact error is a reference's, extrapolated over its
     * levels, so a small shortfall can be the reference's own error as
     * well as the local problems' discretisation the bound is subject to.
     * Nothing without an exact error. */
    void
    record_claimed_bound(const double estimate);

    void
    record_contact_solve(const ContactSolveOutcome &outcome);

    /** One body solved on its own (no contact interface). */
    void
    record_linear_solve(const ElasticBody        &body,
                        const LinearSolverReport &report,
                        const double              wall_time);

    /** The driving estimate and the compared ones ('Compare
     * estimators'). */
    void
    record_error_estimate(const ErrorEstimate                      &estimate,
                          const std::vector<const ErrorEstimate *> &compared,
                          const unsigned int cre_degree_increase);

    /** Announce the reference solution of @p refinements refinements
     * before it is computed (it takes a while). */
    void
    announce_reference_solution(const unsigned int refinements);

    /** The exact error against the reference @p reference: the driving
     * estimator's comparison first, then the compared estimators' (each
     * against the exact error of its own corrected solution). */
    void
    record_exact_error(
      const std::string &reference,
      const std::vector<std::pair<ErrorEstimator, ExactErrorComparison>>
        &comparisons);

    /** The reference solution's own error and the energy check
     * epsilon_energy (from the strain energies @p energy of the solution
     * and @p reference_energy of the reference). */
    void
    record_reference_solution(const ReferenceSolutionStress &reference,
                              const double                   energy,
                              const double                   reference_energy,
                              const double                   epsilon_energy);

    /** Body @p b's error against its exact displacement. */
    void
    record_body_error(const unsigned int      b,
                      const ElasticBody      &body,
                      const ElasticityErrors &errors);

    void
    record_strain_energy(const unsigned int b, const double energy);

    /** Close the cycle: wall and phase times, memory, the cycle's record
     * appended to summary.json, the per-cycle log line and the table's
     * row. */
    void
    end_cycle(const ErrorEstimate &estimate, const bool has_contact);

    /** Why the adaptation stops after cycle @p cycle (summary.json
     * `status` "completed"). */
    void
    record_stop(const unsigned int cycle, const std::string &reason);

    /** The run stops on an error in cycle @p cycle (RunSummary::
     * record_failure); returns a failure to write summary.json. */
    std::string
    record_failure(const unsigned int cycle, const std::string &message);

    /** The table of all cycles. */
    void
    print_table();

  private:
    void
    record_correction(const CorrectedContactSolution &correction);
    /** The log line (if any) on how the cre estimator's R_c on quadratic
     * segments was put in the cone; returns the summary's record. */
    nlohmann::json
    log_bernstein_traction(
      const BernsteinContactTraction::Report &report) const;
    /** The log lines of the cre estimator's equilibration and edge
     * traction optimisation (@p e is a cre estimate). */
    void
    log_equilibration(const ErrorEstimate &e,
                      const unsigned int   cre_degree_increase) const;
    /** The log line on the cre kinematic side's penetration between the
     * mortar's nodes and its opening; returns the summary's record of
     * it. */
    nlohmann::json
    log_kinematic_admissibility(const ErrorEstimate &e);

    const MPI_Comm            mpi_communicator;
    const ConditionalOStream &pcout;
    const TimerOutput        &timer;
    RunSummary                summary;

    unsigned int                  cycle = 0;
    Timer                         cycle_timer;
    std::map<std::string, double> times_before;
    nlohmann::json                record;
    nlohmann::json                body_records;
    types::global_dof_index       n_dofs_of_cycle = 0;
    /** One row per cycle, printed at the end. */
    TableHandler table;

    units::Scales         scales;
    std::set<std::string> scaled_keys;
  };
} // namespace coulomb_adapt

#endif
