#ifndef coulomb_adapt_adaptation_optimal_size_h
#define coulomb_adapt_adaptation_optimal_size_h

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <coulomb_adapt/bodies/elastic_body.h>
#include <coulomb_adapt/contact/contact_state.h>
#include <coulomb_adapt/indicator/error_estimate.h>

#include <array>
#include <cmath>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The optimal mesh of theory.md section 4 for a prescribed accuracy,
   * as a size ratio r_E = h*_E / h_E per cell of each body.
   */
  struct OptimalSizeRatios
  {
    /** r_E per active cell (entries of locally owned cells). */
    std::array<Vector<double>, 2> ratio;
    /** The local convergence rate q_E used. */
    std::array<Vector<double>, 2> rate;
    /** Predicted cell count sum_E r_E^-d of the optimal mesh (both bodies,
     * all ranks), after bounding. */
    double predicted_n_cells = 0;
    /** Predicted epsilon sqrt(sum_E r_E^2q epsilon_E^2), after bounding:
     * epsilon_0 unless the bounds prevent it. */
    double predicted_epsilon = 0;
    /** Cells whose rate was reduced (singular points). */
    unsigned int n_singular_cells = 0;
    /** Cells at the lower / upper bound of r_E. */
    unsigned int n_at_min_ratio = 0, n_at_max_ratio = 0;
    /** Whether the optimal mesh for epsilon_0 had more cells than allowed,
     * and the mesh is the optimal one with that many cells instead. */
    bool limited_by_max_n_cells = false;
    /** Whether the optimal mesh for epsilon_0 had fewer cells than
     * min_n_cells, and the optimal mesh of that many is taken instead. */
    bool limited_by_min_n_cells = false;
  };

  /**
   * The lower bound of r_E in one cycle: @p min_ratio, and
   * @p min_ratio^{3/2} in cells whose rate is reduced at a singular point
   * (OptimalSizePlanner says why).
   */
  inline double
  lowest_size_ratio(const double min_ratio, const bool at_singular_point)
  {
    return at_singular_point ? std::pow(min_ratio, 1.5) : min_ratio;
  }

  /**
   * Whether the error of @p cell falls at the singular rate near the
   * singular point @p p: the point lies in the cell, or closer to it than
   * half the cell's diameter (the distance to its straight faces).
   *
   * Why not only the cells that touch the point: the end of the contact
   * zone lies on the other body's contact face, a straight line that gmsh
   * meshes without a node there, and the nearest node can lie a few
   * hundredths of a cell from the point. The cells around that node are
   * as close to the singularity as those that touch it. On punch (remesh,
   * epsilon_0 = 0.25 %) these cells of the block held most of the error
   * near the punch's corners, and between two cycles their error fell with
   * the refinement ratio to the power 0.2-0.8 instead of q = p = 1, while
   * the cells 0.7 diameters and more from the corner fell at 0.75-1.5
   * (benchmarks/adaptation_steps, "Cells near a singular point").
   */
  bool
  near_singular_point(const Triangulation<2>::active_cell_iterator &cell,
                      const Point<2>                               &p);



  /**
   * Points where the displacement is expected to be singular, the same on
   * every rank: the ends of the active contact zone (from @p contact_states,
   * may be empty), and the boundary vertices where a clamped or a contact
   * boundary part meets a part with another boundary id.
   */
  std::vector<Point<2>>
  find_singular_points(const std::array<const ElasticBody *, 2> &bodies,
                       const std::vector<ContactNodeState> &contact_states);

  /**
   * Minimise the cell count sum_E r_E^-d subject to the predicted error
   * sum_E r_E^{2 q_E} epsilon_E^2 = epsilon_0^2 (d = 2), with r_E <=
   * max_ratio in the optimisation and a lower bound imposed afterwards
   * (the predicted epsilon is then above epsilon_0 and the next cycle goes
   * on): r_E >= min_ratio where q_E = p and r_E >= min_ratio^{3/2} at
   * singular points, where the error falls more slowly with h. q_E = p
   * (the degree) except in cells near a singular point
   * (near_singular_point), where q_E = min(p, singular_rate). With one
   * q for all cells this is the closed form of theory.md section 4; with
   * several, the Lagrange condition r_E^{2 q_E + d} = d / (2 Lambda q_E
   * epsilon_E^2) holds in every cell and the multiplier Lambda is found by
   * bisection (the predicted error is monotone in it).
   *
   * If that mesh would have more than max_n_cells cells (0: no limit),
   * Lambda is lowered until it has at most that many: the same Lagrange
   * condition, so the mesh of the least predicted error for that cell
   * count. Without the limit, a small epsilon_0 asks for a mesh that
   * min_ratio lets grow up to 1/min_ratio^2 = 100-fold in one cycle.
   * Likewise, with fewer than min_n_cells cells (0: no minimum) Lambda is
   * raised until it has that many: a large epsilon_0 with the
   * over-refinement rule coarsened blocks to 4 + 4 triangles, where the
   * recovered stress is the FE stress and the contact zone one segment.
   *
   * The cells' epsilon_E^2 and q_E are gathered once, at construction:
   * the adaptation plans a second time with a relaxed lower bound when
   * the first plan falls short of its aim, and finding the cells near
   * the singular points was most of a plan's time (benchmarks/
   * adaptive_run).
   */
  class OptimalSizePlanner
  {
  public:
    OptimalSizePlanner(const std::array<const ElasticBody *, 2> &bodies,
                       const ErrorEstimate                      &estimate,
                       const std::vector<Point<2>> &singular_points,
                       const unsigned int           degree,
                       const double                 singular_rate);

    OptimalSizeRatios
    plan(const double target_error,
         const double min_ratio,
         const double max_ratio,
         const double max_n_cells = 0,
         const double min_n_cells = 0) const;

    /** Per owned cell of both bodies: epsilon_E^2 / D^2 and q_E. */
    struct Cell
    {
      unsigned int body, index;
      double       epsilon_squared, rate;
    };

  private:
    MPI_Comm                      comm;
    unsigned int                  degree;
    std::vector<Cell>             cells;
    std::array<Vector<double>, 2> rate;
    std::array<unsigned int, 2>   n_active_cells;
    unsigned int                  n_singular_cells;
  };
} // namespace coulomb_adapt

#endif
