#include <coulomb_adapt/adaptation/optimal_size.h>
#include <coulomb_adapt/output/cycle_report.h>

#include <cmath>
#include <iomanip>

// The mesh part of a cycle's report: the adaptation's plan and what it
// gave, the meshes of the cycle (the log lines and summary.json's
// "bodies" and "adaptation" records).
namespace coulomb_adapt
{
  // The plan (the optimal mesh for epsilon_0 and how the size ratios were
  // bounded) for the size-ratio strategies, the flags for refine.
  void
  CycleReport::record_mesh_adaptation(const MeshAdaptationReport   &r,
                                      const parameters::Adaptation &a,
                                      const unsigned int            degree,
                                      const double                  calibration)
  {
    pcout << "  adapt (" << option_name(r.strategy);
    if (r.strategy == AdaptationStrategy::refine)
      pcout << ", " << option_name(a.refinement_criterion);
    pcout << "): ";
    if (r.predicted_n_cells >= 0)
      pcout << "optimal mesh for epsilon_0 = " << 100 * a.target_error
            << " %, planned for " << std::setprecision(3)
            << 100 * r.aimed_epsilon << " % (safety factor "
            << a.target_safety_factor << ", measured/predicted " << calibration
            << "): N* = " << std::llround(r.predicted_n_cells)
            << " cells, predicted epsilon " << std::setprecision(3)
            << 100 * r.predicted_epsilon << " % (r_E bounded to ["
            << r.min_size_ratio << " ("
            << lowest_size_ratio(r.min_size_ratio, true)
            << " near singular points), " << a.max_size_ratio
            << "]: " << r.n_at_min_ratio << " cells at the lower, "
            << r.n_at_max_ratio << " at the upper bound; q reduced to "
            << std::min<double>(degree, a.singular_rate) << " in "
            << r.n_singular_cells << " cells near singular points)";
    if (r.unrelaxed_predicted_epsilon > 0)
      pcout << "; lower bound relaxed from " << a.min_size_ratio
            << " (the model checked on the last mesh, the plan with it "
               "predicted "
            << std::setprecision(3) << 100 * r.unrelaxed_predicted_epsilon
            << " %, above the aim)";
    if (r.limited_by_max_dofs)
      pcout << "; more cells than 'Maximum number of DoFs' = " << a.max_dofs
            << " allows: the optimal mesh of that size instead (predicted "
               "epsilon above epsilon_0)";
    if (r.limited_by_min_cells)
      pcout << "; fewer cells than 'Minimum number of cells' = " << a.min_cells
            << ": the optimal mesh of that many instead (predicted epsilon "
               "below the aim)";
    if (r.strategy == AdaptationStrategy::refine)
      pcout << (r.predicted_n_cells >= 0 ? "; " : "") << r.n_refine_flags
            << " cells flagged for refinement, " << r.n_coarsen_flags
            << " for coarsening";
    if (r.strategy == AdaptationStrategy::uniform)
      pcout << "every cell refined once";
    if (r.n_triangle_splits[0] + r.n_triangle_splits[1] > 0)
      pcout << "; gmsh meshed at 2^k times the sizes, each triangle split "
               "into 4 k times (k = "
            << r.n_triangle_splits[0] << ", " << r.n_triangle_splits[1] << ")";
    pcout << std::endl;
  }



  void
  CycleReport::record_meshes(const std::array<const ElasticBody *, 2> &bodies,
                             const AdaptationStrategy                  strategy,
                             const MeshAdaptationReport *last_adaptation,
                             const double                calibration)
  {
    pcout << "Cycle " << cycle << std::endl;
    record["strategy"] = option_name(strategy);
    for (const ElasticBody *body : bodies)
      {
        const auto n_cells     = body->triangulation().n_global_active_cells();
        const auto n_vertices  = body->n_vertices();
        const auto n_body_dofs = body->dof_handler().n_dofs();
        n_dofs_of_cycle += n_body_dofs;
        pcout << "  " << body->name() << ": " << n_cells << " cells, "
              << n_vertices << " vertices, " << n_body_dofs << " DoFs ("
              << body->dof_handler().get_fe().get_name() << ")" << std::endl;
        body_records.push_back({{"name", body->name()},
                                {"n_cells", n_cells},
                                {"n_vertices", n_vertices},
                                {"n_dofs", n_body_dofs}});
      }
    if (last_adaptation == nullptr)
      return;
    const MeshAdaptationReport &a = *last_adaptation;
    if (a.predicted_n_cells >= 0)
      {
        const double obtained =
          bodies[0]->triangulation().n_global_active_cells() +
          bodies[1]->triangulation().n_global_active_cells();
        pcout << "  cells: " << std::llround(obtained)
              << " obtained, N* = " << std::llround(a.predicted_n_cells)
              << " predicted (" << std::showpos << std::setprecision(3)
              << 100 * (obtained / a.predicted_n_cells - 1) << std::noshowpos
              << " %)" << std::endl;
        record["adaptation"] = {{"predicted_n_cells", a.predicted_n_cells},
                                {"predicted_epsilon", a.predicted_epsilon},
                                {"aimed_epsilon", a.aimed_epsilon},
                                {"calibration", calibration},
                                {"obtained_n_cells", obtained},
                                {"singular_cells", a.n_singular_cells},
                                {"min_size_ratio", a.min_size_ratio},
                                {"cells_at_min_ratio", a.n_at_min_ratio},
                                {"limited_by_max_dofs", a.limited_by_max_dofs},
                                {"limited_by_min_cells",
                                 a.limited_by_min_cells}};
      }
    if (a.n_triangle_splits[0] + a.n_triangle_splits[1] > 0)
      record["adaptation"]["triangle_splits"] = a.n_triangle_splits;
    if (a.strategy == AdaptationStrategy::refine)
      {
        record["adaptation"]["refine_flags"]  = a.n_refine_flags;
        record["adaptation"]["coarsen_flags"] = a.n_coarsen_flags;
      }
  }
} // namespace coulomb_adapt
