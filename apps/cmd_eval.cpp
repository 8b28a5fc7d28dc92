// `gridslam eval RELATIONS TRAJECTORY [--json] [--min-dt S] [--max-dt S] [--tolerance S]`: the
// SLAM benchmark's relation metric (DESIGN.md §2, §3.1) of a trajectory file (plain or TUM).
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "gridslam/eval/relation_metric.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/io/trajectory_io.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct EvalArgs {
  std::string relations;
  std::string trajectory;
  bool json = false;
  // Flags override the configuration; applied in RunEval, after --config was read.
  std::optional<double> min_dt;
  std::optional<double> max_dt;
  std::optional<double> tolerance;
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
          {"filtered", m.filtered},
          {"total", m.total},
          {"tolerance", o.tolerance},
          {"min_dt", o.min_dt},
          {"max_dt", o.max_dt}};
}

int RunEval(const EvalArgs& args, AppContext& context) {
  eval::EvalOptions& options = context.options.eval;
  options.min_dt = args.min_dt.value_or(options.min_dt);
  options.max_dt = args.max_dt.value_or(options.max_dt);
  options.tolerance = args.tolerance.value_or(options.tolerance);
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  auto relations = io::ReadRelations(args.relations);
  if (!relations.ok()) {
    return ReportError(relations.error());
  }
  auto trajectory = io::ReadTrajectory(args.trajectory);
  if (!trajectory.ok()) {
    return ReportError(trajectory.error());
  }
  const auto m = eval::EvaluateRelations(relations.value(), trajectory.value(), options);
  if (args.json) {
    std::cout << ToJson(m, options).dump(2) << "\n";
  } else {
    std::printf(
        "translation_mean=%.6f translation_std=%.6f rotation_mean_deg=%.6f rotation_std_deg=%.6f "
        "relations=%ld\n",
        m.translation.mean, m.translation.std, m.rotation_deg.mean, m.rotation_deg.std, m.used);
    std::printf(
        "translation_sq_mean=%.6g translation_sq_std=%.6g rotation_sq_mean_deg2=%.6g "
        "rotation_sq_std_deg2=%.6g missing=%ld filtered=%ld total=%ld\n",
        m.translation_sq.mean, m.translation_sq.std, m.rotation_sq_deg2.mean,
        m.rotation_sq_deg2.std, m.missing, m.filtered, m.total);
  }
  if (m.missing > 0) {
    std::fprintf(stderr,
                 "gridslam: warning: %ld of %ld relations not scored: the trajectory has no pose "
                 "within %.6f s of one of their timestamps\n",
                 m.missing, m.total - m.filtered, options.tolerance);
  }
  if (m.used == 0) {
    return ReportError(InvalidInput("no relation could be scored", args.trajectory));
  }
  return kExitOk;
}

RunFunction SetupEval(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<EvalArgs>();
  sub.add_option("RELATIONS", args->relations, "Relations file (t1 t2 x y z roll pitch yaw)")
      ->required();
  sub.add_option("TRAJECTORY", args->trajectory, "Trajectory (timestamp x y theta, or TUM)")
      ->required();
  sub.add_flag("--json", args->json, "Print one JSON object");
  sub.add_option("--min-dt", args->min_dt, "Score only relations with |t2 - t1| >= S [s]");
  sub.add_option("--max-dt", args->max_dt,
                 "Score only relations with |t2 - t1| < S [s]; 0 = no limit");
  sub.add_option("--tolerance", args->tolerance,
                 "Largest relation/trajectory timestamp difference that matches [s]");
  return [args](AppContext& ctx) { return RunEval(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "eval", "Benchmark relation metric of a trajectory (Kümmerle et al. 2009)", SetupEval});

}  // namespace
}  // namespace gridslam::app
