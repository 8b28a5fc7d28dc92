// `gridslam eval RELATIONS TRAJECTORY [--json] [--min-dt S] [--max-dt S] [--tolerance S]
// [--no-interpolate] [--max-interpolation-gap S]`: the SLAM benchmark's relation metric
// (docs/design.md §2, §3.1) of a trajectory file (plain or TUM). Relation timestamps between two
// trajectory poses are interpolated (reported as `interpolated`), unless --no-interpolate.
// Several robots (issue 8): `gridslam eval RELATIONS TRAJ_0 TRAJ_1 ... [--index index.txt]`
// scores relations within and between robots of a merged map (trajectories in one common
// frame): each timestamp is looked up in the trajectory of the robot index.txt gives it, or,
// without --index, in the first trajectory that holds it (multi_robot/robot_index.hpp).
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/io/simulation_io.hpp"
#include "gridslam/io/trajectory_io.hpp"
#include "gridslam/multi_robot/robot_index.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct EvalArgs {
  std::string relations;
  std::vector<std::string> trajectories;
  std::string index;
  bool json = false;
  // Flags override the configuration; applied in RunEval, after --config was read.
  std::optional<double> min_dt;
  std::optional<double> max_dt;
  std::optional<double> tolerance;
  bool no_interpolate = false;
  std::optional<double> max_interpolation_gap;
};

nlohmann::json ToJson(const eval::RelationMetrics& m, const eval::EvalOptions& o) {
  return {{"translation_mean", m.translation.mean},
          {"translation_std", m.translation.std},
          {"rotation_mean_deg", m.rotation_deg.mean},
          {"rotation_std_deg", m.rotation_deg.std},
          {"translation_sq_mean", m.translation_sq.mean},
          {"translation_sq_std", m.translation_sq.std},
          {"rotation_sq_mean_deg2", m.rotation_sq_deg2.mean},
          {"rotation_sq_std_deg2", m.rotation_sq_deg2.std},
          {"relations", m.used},
          {"missing", m.missing},
          {"interpolated", m.interpolated},
          {"filtered", m.filtered},
          {"total", m.total},
          {"tolerance", o.tolerance},
          {"min_dt", o.min_dt},
          {"max_dt", o.max_dt},
          {"interpolate", o.interpolate},
          {"max_interpolation_gap", o.max_interpolation_gap}};
}

int RunEval(const EvalArgs& args, AppContext& context) {
  eval::EvalOptions& options = context.options.eval;
  options.min_dt = args.min_dt.value_or(options.min_dt);
  options.max_dt = args.max_dt.value_or(options.max_dt);
  options.tolerance = args.tolerance.value_or(options.tolerance);
  options.interpolate = options.interpolate && !args.no_interpolate;
  options.max_interpolation_gap =
      args.max_interpolation_gap.value_or(options.max_interpolation_gap);
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  auto relations = io::ReadRelations(args.relations);
  if (!relations.ok()) {
    return ReportError(relations.error());
  }
  std::vector<std::vector<io::StampedPose>> trajectories;
  for (const std::string& path : args.trajectories) {
    auto trajectory = io::ReadTrajectory(path);
    if (!trajectory.ok()) {
      return ReportError(trajectory.error());
    }
    trajectories.push_back(std::move(trajectory).value());
  }
  multi_robot::RobotIndex index;
  if (!args.index.empty()) {
    auto entries = io::ReadScanIndex(args.index);
    if (!entries.ok()) {
      return ReportError(entries.error());
    }
    std::vector<std::pair<Time, int>> pairs;
    for (const io::ScanIndexEntry& e : entries.value()) {
      if (e.robot < 0 || e.robot >= static_cast<int>(trajectories.size())) {
        return ReportError(InvalidInput("robot " + std::to_string(e.robot) + " at " +
                                            FormatSeconds(e.time) + " has no trajectory (" +
                                            std::to_string(trajectories.size()) + " given)",
                                        args.index));
      }
      pairs.emplace_back(e.time, e.robot);
    }
    index = multi_robot::RobotIndex(pairs);
  }
  multi_robot::CombineStats combined_stats;
  const std::vector<io::StampedPose> combined =
      trajectories.size() == 1 && index.empty()
          ? std::move(trajectories.front())
          : multi_robot::CombineTrajectories(trajectories, index,
                                             SecondsToDuration(options.tolerance), &combined_stats);
  if (trajectories.size() > 1 || !index.empty()) {
    // The combined trajectory interleaves robots: a pose between two of them is no pose.
    options.interpolate = false;
  }
  const auto m = eval::EvaluateRelations(relations.value(), combined, options);
  if (args.json) {
    nlohmann::json json = ToJson(m, options);
    if (args.trajectories.size() > 1 || !index.empty()) {
      json["trajectories"] = args.trajectories.size();
      json["poses_dropped_by_index"] = combined_stats.dropped;
      json["shared_timestamps"] = combined_stats.shared_times;
    }
    std::cout << json.dump(2) << "\n";
  } else {
    std::printf(
        "translation_mean=%.6f translation_std=%.6f rotation_mean_deg=%.6f rotation_std_deg=%.6f "
        "relations=%ld\n",
        m.translation.mean, m.translation.std, m.rotation_deg.mean, m.rotation_deg.std, m.used);
    std::printf(
        "translation_sq_mean=%.6g translation_sq_std=%.6g rotation_sq_mean_deg2=%.6g "
        "rotation_sq_std_deg2=%.6g missing=%ld filtered=%ld total=%ld interpolated=%ld\n",
        m.translation_sq.mean, m.translation_sq.std, m.rotation_sq_deg2.mean,
        m.rotation_sq_deg2.std, m.missing, m.filtered, m.total, m.interpolated);
  }
  if (m.missing > 0) {
    std::fprintf(stderr,
                 "gridslam: warning: %ld of %ld relations not scored: the trajectory has no pose "
                 "within %.6f s of one of their timestamps%s\n",
                 m.missing, m.total - m.filtered, options.tolerance,
                 options.interpolate ? " and none to interpolate between" : "");
  }
  if (m.interpolated > 0) {
    std::fprintf(stderr,
                 "gridslam: note: %ld of %ld scored relations use a pose interpolated between two "
                 "trajectory poses (at most %.3f s apart; --no-interpolate to turn off)\n",
                 m.interpolated, m.used, options.max_interpolation_gap);
  }
  if (combined_stats.shared_times > 0) {
    std::fprintf(stderr,
                 "gridslam: warning: %ld timestamps appear in several trajectories; each is "
                 "scored with the first trajectory's pose (give --index to choose)\n",
                 combined_stats.shared_times);
  }
  if (m.used == 0) {
    return ReportError(InvalidInput("no relation could be scored", args.trajectories.front()));
  }
  return kExitOk;
}

RunFunction SetupEval(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<EvalArgs>();
  sub.add_option("RELATIONS", args->relations, "Relations file (t1 t2 x y z roll pitch yaw)")
      ->required();
  sub.add_option("TRAJECTORY", args->trajectories,
                 "Trajectory (timestamp x y theta, or TUM); several robots' trajectories of one "
                 "merged map score relations between robots")
      ->required();
  sub.add_option("--index", args->index,
                 "index.txt (timestamp robot): which trajectory holds each timestamp (robot i = "
                 "the i-th TRAJECTORY)");
  sub.add_flag("--json", args->json, "Print one JSON object");
  sub.add_option("--min-dt", args->min_dt, "Score only relations with |t2 - t1| >= S [s]");
  sub.add_option("--max-dt", args->max_dt,
                 "Score only relations with |t2 - t1| < S [s]; 0 = no limit");
  sub.add_option("--tolerance", args->tolerance,
                 "Largest relation/trajectory timestamp difference that matches [s]");
  sub.add_flag("--no-interpolate", args->no_interpolate,
               "Score only relations whose timestamps have trajectory poses (no interpolation)");
  sub.add_option("--max-interpolation-gap", args->max_interpolation_gap,
                 "Interpolate only between poses at most S seconds apart; 0 = any gap");
  return [args](AppContext& ctx) { return RunEval(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "eval", "Benchmark relation metric of a trajectory (Kümmerle et al. 2009)", SetupEval});

}  // namespace
}  // namespace gridslam::app
