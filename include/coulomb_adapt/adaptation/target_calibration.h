#ifndef coulomb_adapt_adaptation_target_calibration_h
#define coulomb_adapt_adaptation_target_calibration_h

namespace coulomb_adapt
{
  /**
   * The epsilon that the next optimal mesh should be planned for, so that
   * the mesh it builds reaches epsilon_0 in as few cycles as possible.
   *
   * The optimal-mesh plan of theory.md section 4 predicts the error of the
   * new mesh from the model epsilon_E(h*) = r_E^{q_E} epsilon_E(h), with an
   * a-priori rate q_E per cell. The model is only asymptotic: at singular
   * points, on coarse meshes and where the error moves between cells (the
   * contact zone's ends shift as the mesh changes) the new mesh's epsilon
   * lands above or below the prediction. Each plan is therefore made for
   *
   *   aim = safety * epsilon_0 / c,   c = epsilon_achieved / epsilon_predicted
   *
   * where c is the ratio of the error measured on the last planned mesh to
   * what its plan predicted (1 before any plan has been checked): a
   * global correction of the model. The safety factor keeps the step after
   * a correction from landing just above the target because c itself
   * changes a little from one cycle to the next. For the same reason a
   * correction below 1 is believed only beyond the safety margin: c is
   * replaced by min(1, c / safety), so that c in [safety, 1) leaves the
   * aim at safety * epsilon_0 instead of planning for more than that
   * (a plan for above epsilon_0 misses it as soon as c moves back towards
   * 1, and a miss costs a whole cycle).
   */
  class TargetCalibration
  {
  public:
    /** @p safety_factor in (0, 1]: the plan aims at this fraction of
     * epsilon_0 (times the correction). */
    explicit TargetCalibration(const double safety_factor);

    /** The epsilon to plan the next mesh for: safety * epsilon_0 / c,
     * with c < 1 replaced by min(1, c / safety). */
    double
    aim(const double target_error) const;

    /** The plan just made predicts @p predicted_epsilon for the new mesh. */
    void
    record_plan(const double predicted_epsilon);

    /** The new mesh's estimated epsilon: updates the correction if a plan
     * was recorded since the last call. */
    void
    record_achieved(const double epsilon);

    /** The current correction c (1 until a plan has been checked). */
    double
    correction() const;

    /** Whether a plan has been checked against the mesh it built: the
     * model's error is then known, and a plan may refine further in one
     * step (adapt_meshes). */
    bool
    model_checked() const;

  private:
    double safety_factor;
    /** Bounds of c: a plan missed by more than a factor 2 says more about
     * the model (a changed contact zone, a mesh too coarse for the
     * estimator) than a global factor can fix. */
    static constexpr double min_correction = 0.5, max_correction = 2;
    double                  correction_factor  = 1;
    double                  pending_prediction = -1;
    bool                    checked            = false;
  };
} // namespace coulomb_adapt

#endif
