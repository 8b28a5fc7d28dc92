#include "app_map_report.hpp"

#include "gridslam/common/time.hpp"

#include "app_mounting_report.hpp"

namespace gridslam::app {

nlohmann::json StatsJson(const pipeline::MapperStats& s) {
  return {
      {"frames", s.frames},
      {"key_maps", s.key_maps},
      {"featureless_key_maps", s.featureless},
      {"sequential_edges_aligned", s.sequential_aligned},
      {"closures",
       {{"proposed", s.candidates + s.appearance_candidates + s.verification_alignments},
        {"prior_candidates", s.candidates},
        {"verification_alignments", s.verification_alignments},
        {"appearance_queries", s.appearance_queries},
        {"appearance_candidates", s.appearance_candidates},
        {"verified", s.verified},
        {"found_by_prior_refinement", s.prior_refined},
        {"prior_searches", s.prior_searches},
        {"prior_wide_searches", s.prior_wide_searches},
        {"found_by_prior_wide_search", s.prior_wide_found},
        {"prior_ridges", s.prior_ridges},
        {"prior_weak_by_search", s.prior_weak_by_search},
        {"verified_loops", s.verified_loops},
        {"key_map_fields_recomputed", s.geometry_recomputed},
        {"window_refinements", s.window_refinements},
        {"window_refined", s.window_refined},
        {"online_full_optimizations", s.online_full_optimizations},
        {"accepted", s.accepted},
        {"rejected_gate", s.rejected_gate},
        {"rejected_beyond_drift", s.closures_beyond_drift},
        {"rejected_alignment",
         s.candidates + s.appearance_candidates + s.verification_alignments - s.verified},
        {"pruned", s.pruned}}},
      {"joins", s.joins},
      {"joins_refused_free_space", s.joins_refused_free_space},
      {"odometry",
       {{"doubtful", s.odometry_doubtful},
        {"overruled", s.odometry_overruled},
        {"missing", s.odometry_missing},
        {"wide_searches", s.wide_searches},
        {"poor_matches", s.poor_matches},
        {"poor_rescued", s.poor_rescued},
        {"poor_ambiguous", s.poor_ambiguous}}},
      {"degenerate_matches", {{"one_direction", s.degenerate_one}, {"both", s.degenerate_both}}},
      {"far_window_matches", s.far_matches},
      {"wall_normal_frames", s.wall_normal_frames},
      {"chi2_final", s.chi2_final},
      {"time_s",
       {{"front_end", s.seconds_front_end},
        {"description", s.seconds_description},
        {"alignment", s.seconds_alignment},
        {"online_optimization", s.seconds_optimization},
        {"final_optimization", s.seconds_final},
        {"fusion", s.seconds_fusion},
        {"cpu_worker", s.cpu_seconds_worker},
        {"caller_blocked", s.seconds_caller_blocked},
        {"worker_idle", s.seconds_worker_idle}}}};
}

nlohmann::json MapReport(const pipeline::MapperResult& result,
                         const std::vector<RobotOutput>& robots) {
  nlohmann::json report = StatsJson(result.stats);
  report["schema_version"] = kReportSchemaVersion;
  nlohmann::json logs = nlohmann::json::array();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    logs.push_back({{"log", robots[r].log},
                    {"robot", r},
                    {"scans", robots[r].scans},
                    {"duration_s", robots[r].duration},
                    {"skipped_malformed_lines", robots[r].skipped_malformed},
                    {"repaired_timestamps", robots[r].repaired_timestamps}});
    if (r < result.mountings.size()) {
      logs.back()["laser_mounting"] = MountingJson(result.mountings[r]);
    }
  }
  report["logs"] = logs;
  nlohmann::json joins = nlohmann::json::array();
  for (const pipeline::JoinRecord& j : result.joins) {
    joins.push_back({{"robots", {j.robot_a, j.robot_b}},
                     {"time", FormatSeconds(j.time)},
                     {"vertices", {j.vertex_a, j.vertex_b}},
                     {"matches", j.matches}});
  }
  report["robot_joins"] = joins;
  return report;
}

}  // namespace gridslam::app
