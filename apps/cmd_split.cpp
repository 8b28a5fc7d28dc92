// `gridslam split LOG -n N [--relations FILE] [--overlap S] [--by scans|time] [--max-offset M]
// --seed S -o DIR` (issue 8; docs/design.md §2): one log becomes N robots with unknown relative
// starts. DIR receives robot_<i>.clf (piece i in its own, randomly placed odometry frame, as ODOM +
// ROBOTLASER1 lines; printed timestamps unchanged), index.txt (`timestamp robot`: every scan with
// its home robot, in time order) and split.json (the pieces, their scans and the transforms
// T_new_old, i.e. the answer); with --relations also within.relations, between.relations and
// robot_<i>.relations (the relations by the home robots of their timestamps; docs/multi_robot.md).
// Every input is checked before anything is written: bad input exits 2 with file:line and leaves
// DIR untouched.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/io/simulation_io.hpp"
#include "gridslam/multi_robot/log_split.hpp"
#include "gridslam/multi_robot/piece_log.hpp"
#include "gridslam/multi_robot/relation_split.hpp"
#include "gridslam/recording/recording_reader.hpp"

#include "app_output_dir.hpp"
#include "command.hpp"

namespace gridslam::app {
namespace {

namespace fs = std::filesystem;

struct SplitArgs {
  std::string log;
  int pieces = 0;
  std::string relations;
  std::optional<double> overlap;
  std::optional<std::string> by;
  std::optional<double> max_offset;
  std::uint64_t seed = 1;
  std::string output;
};

nlohmann::json PoseJson(const Pose2& pose) { return {pose.x(), pose.y(), pose.theta()}; }

nlohmann::json PieceJson(const std::vector<Frame>& frames, const multi_robot::SplitPiece& piece,
                         int index) {
  const Frame& first = frames[piece.begin];
  const Frame& last = frames[piece.end - 1];
  return {{"robot", index},
          {"log", "robot_" + std::to_string(index) + ".clf"},
          {"scans", piece.end - piece.begin},
          {"home_scans", piece.core_end - piece.core_begin},
          {"first_time", FormatSeconds(first.time)},
          {"home_first_time", FormatSeconds(frames[piece.core_begin].time)},
          {"last_time", FormatSeconds(last.time)},
          {"duration_s", ToSeconds(last.corrected_time - first.corrected_time)},
          {"T_new_old", PoseJson(piece.T_new_old)},
          {"start_pose", PoseJson(piece.T_new_old * first.T_odom_base)}};
}

int RunSplit(const SplitArgs& args, AppContext& context) {
  multi_robot::SplitOptions& options = context.options.split;
  options.overlap = args.overlap.value_or(options.overlap);
  options.by = args.by.value_or(options.by);
  options.max_translation = args.max_offset.value_or(options.max_translation);
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  if (args.pieces < 1) {
    return ReportError(InvalidInput("-n must be at least 1"));
  }
  // 1. Read and check everything.
  io::CarmenStats log_stats;
  auto frames = recording::ReadRecording(args.log, context.Recording(), &log_stats);
  if (!frames.ok()) {
    return ReportError(frames.error());
  }
  if (frames.value().empty()) {
    return ReportError(io::NoScansError(args.log, log_stats));
  }
  std::optional<std::vector<eval::Relation>> relations;
  if (!args.relations.empty()) {
    auto read = io::ReadRelations(args.relations);
    if (!read.ok()) {
      return ReportError(read.error());
    }
    relations = std::move(read).value();
  }
  auto plan = multi_robot::PlanSplit(frames.value(), args.pieces, args.seed, options);
  if (!plan.ok()) {
    Error error = plan.error();
    error.file = args.log;
    return ReportError(error);
  }
  const std::vector<Frame>& all = frames.value();
  std::vector<io::ScanIndexEntry> index;
  std::vector<std::pair<Time, int>> home;
  for (std::size_t k = 0; k < all.size(); ++k) {
    index.push_back({all[k].time, plan.value().home[k]});
    home.emplace_back(all[k].time, plan.value().home[k]);
  }
  std::stable_sort(index.begin(), index.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  const Duration tolerance = SecondsToDuration(context.options.eval.tolerance);
  std::optional<multi_robot::RelationSplit> split;
  if (relations) {
    split = multi_robot::SplitRelations(*relations, multi_robot::RobotIndex(home), args.pieces,
                                        tolerance);
    if (split->within.size() + split->between.size() == 0) {
      return ReportError(
          InvalidInput("no relation has both timestamps in the log", args.relations));
    }
    if (split->unmatched > 0) {
      std::fprintf(stderr,
                   "gridslam split: warning: %ld of %zu relations have a timestamp that is no "
                   "scan of the log (within %.6f s); they are left out\n",
                   split->unmatched, relations->size(), context.options.eval.tolerance);
    }
  }

  // 2. Write.
  auto output = OutputDir::Begin(args.output);  // staged, committed at the end (issue 17)
  if (!output.ok()) {
    return ReportError(output.error());
  }
  const fs::path dir(output.value()->path());
  nlohmann::json report = {{"log", args.log},
                           {"scans", all.size()},
                           {"pieces", args.pieces},
                           {"seed", args.seed},
                           {"by", options.by},
                           {"overlap_s", options.overlap},
                           {"max_translation", options.max_translation}};
  report["robots"] = nlohmann::json::array();
  for (int i = 0; i < args.pieces; ++i) {
    const multi_robot::SplitPiece& piece = plan.value().pieces[static_cast<std::size_t>(i)];
    const std::string name = "robot_" + std::to_string(i) + ".clf";
    const std::string comment = "gridslam split: piece " + std::to_string(i) + " of " +
                                std::to_string(args.pieces) + " of " + args.log + ", seed " +
                                std::to_string(args.seed) +
                                "; odometry moved by an unknown rigid transform (split.json)";
    if (const Status s = multi_robot::WritePieceLog((dir / name).string(),
                                                    multi_robot::PieceFrames(all, piece), comment);
        !s.ok()) {
      return ReportError(s.error());
    }
    report["robots"].push_back(PieceJson(all, piece, i));
  }
  if (const Status s = io::WriteScanIndex((dir / "index.txt").string(), index); !s.ok()) {
    return ReportError(s.error());
  }
  if (split) {
    for (const Status& s :
         {io::WriteRelations((dir / "within.relations").string(), split->within),
          io::WriteRelations((dir / "between.relations").string(), split->between)}) {
      if (!s.ok()) {
        return ReportError(s.error());
      }
    }
    for (int i = 0; i < args.pieces; ++i) {
      const std::string name = "robot_" + std::to_string(i) + ".relations";
      if (const Status s = io::WriteRelations((dir / name).string(),
                                              split->per_robot[static_cast<std::size_t>(i)]);
          !s.ok()) {
        return ReportError(s.error());
      }
    }
    report["relations"] = {{"file", args.relations},
                           {"total", relations->size()},
                           {"within", split->within.size()},
                           {"between", split->between.size()},
                           {"unmatched", split->unmatched}};
  }
  if (const Status s =
          io::WriteFileAtomically((dir / "split.json").string(), report.dump(2) + "\n");
      !s.ok()) {
    return ReportError(s.error());
  }
  if (const Status s = output.value()->Commit(); !s.ok()) {
    return ReportError(s.error());
  }
  std::printf("gridslam split: %zu scans of %s into %d robots (seed %llu, by %s, overlap %.1f s)\n",
              all.size(), args.log.c_str(), args.pieces, static_cast<unsigned long long>(args.seed),
              options.by.c_str(), options.overlap);
  for (int i = 0; i < args.pieces; ++i) {
    const auto& r = report["robots"][static_cast<std::size_t>(i)];
    std::printf("  robot %d: %zu scans (%zu home), %.1f s\n", i, r["scans"].get<std::size_t>(),
                r["home_scans"].get<std::size_t>(), r["duration_s"].get<double>());
  }
  if (split) {
    std::printf("  relations: %zu within, %zu between, %ld without a scan in the log\n",
                split->within.size(), split->between.size(), split->unmatched);
  }
  std::printf("outputs in %s\n", args.output.c_str());
  return kExitOk;
}

RunFunction SetupSplit(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<SplitArgs>();
  sub.add_option("LOG", args->log,
                 "Recording: CARMEN log (optionally gzip) or bag (.bag, .mcap, rosbag2)")
      ->required();
  sub.add_option("-n,--pieces", args->pieces, "Number of robots (consecutive pieces)")->required();
  sub.add_option("--relations", args->relations,
                 "Benchmark relations of LOG, split into within/between.relations");
  sub.add_option("--overlap", args->overlap,
                 "Seconds consecutive pieces share (default: split.overlap)");
  sub.add_option("--by", args->by, "Cut into equal scan counts (scans) or durations (time)");
  sub.add_option("--max-offset", args->max_offset,
                 "Piece starts: x, y within +-M metres (default: split.max_translation)");
  sub.add_option("--seed", args->seed, "Random seed of the starts (default 1)");
  sub.add_option("-o,--output", args->output, "Output folder")->required()->check(OutputFolder());
  return [args](AppContext& ctx) { return RunSplit(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "split", "Cut one log into N robots with unknown relative starts (multi-robot tests)",
    SetupSplit});

}  // namespace
}  // namespace gridslam::app
