// `gridslam map LOG [LOG ...] -o DIR [--config FILE]`: the whole system (docs/design.md §1, §2).
// Each LOG is one robot with its own odometry frame and unknown start; their frames are processed
// interleaved by time, as a team would deliver them. Writes the map(s), the corrected
// trajectories, the optimized graph, the effective configuration and a report into DIR.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/map_io.hpp"
#include "gridslam/pipeline/frame_interleaver.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/recording/recording_reader.hpp"

#include "app_align_map.hpp"
#include "app_map_session.hpp"
#include "app_memory.hpp"
#include "app_mounting_report.hpp"
#include "app_output_dir.hpp"
#include "command.hpp"
#include <time.h>
#include <unistd.h>

namespace gridslam::app {
namespace {

using Clock = std::chrono::steady_clock;

/// One progress line on a terminal: share of the logs read, elapsed time, ETA, scans/s.
void PrintProgress(double fraction, double elapsed, const pipeline::MapperStats& s) {
  const double rate = elapsed > 0.0 ? static_cast<double>(s.frames) / elapsed : 0.0;
  const double eta = fraction > 0.01 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr,
               "\rgridslam map: %3.0f%% of the log, %.0f s elapsed, ETA %.0f s, %.0f scans/s; "
               "%ld key maps, %ld loop closures ",
               100.0 * fraction, elapsed, eta, rate, s.key_maps, s.accepted);
  std::fflush(stderr);
}

struct MapArgs {
  std::vector<std::string> logs;
  std::string output;
  bool align_map = false;
  double snapshot_period = 0.0;  ///< --snapshots [s of log time], 0 = none.
};

/// CPU time of the calling thread [s] (snapshot costs, robust to other load on the machine).
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// `gridslam map --snapshots S`: writes the map of every component every S seconds of log time
/// into a folder (snapshot_00000.png, ...; component c > 0: snapshot_00000_c<c>.png), through
/// the Mapper's online API (Mapper::Snapshot), and times each snapshot.
class SnapshotWriter {
 public:
  SnapshotWriter(std::filesystem::path dir, double period, const fusion::FusionOptions& fusion)
      : dir_(std::move(dir)), period_(period), fusion_(fusion) {}

  Status AfterFrame(pipeline::Mapper& mapper, Time time) {
    if (period_ <= 0.0) {
      return Status::Ok();
    }
    if (!start_) {
      start_ = time;
    }
    if (ToSeconds(time - *start_) < period_ * static_cast<double>(written_ + 1)) {
      return Status::Ok();
    }
    const auto begin = Clock::now();
    const double cpu_begin = ThreadCpuSeconds();
    const pipeline::MapSnapshot snapshot = mapper.Snapshot();
    cpu_seconds_.push_back(ThreadCpuSeconds() - cpu_begin);
    seconds_.push_back(std::chrono::duration<double>(Clock::now() - begin).count());
    replaced_ += snapshot.key_maps_replaced;
    for (std::size_t c = 0; c < snapshot.maps.size(); ++c) {
      if (snapshot.maps[c].size() == 0) {
        continue;
      }
      char name[64];
      std::snprintf(name, sizeof(name), c == 0 ? "snapshot_%05ld.png" : "snapshot_%05ld_c%zu.png",
                    written_, c);
      GRIDSLAM_RETURN_IF_ERROR(io::WriteMapImage((dir_ / name).string(),
                                                 fusion::ToOccupancy(snapshot.maps[c], fusion_)));
    }
    ++written_;
    return Status::Ok();
  }

  /// Counts and the cost per snapshot (wall and this thread's CPU time; maps not included).
  [[nodiscard]] nlohmann::json Json() const {
    const auto summary = [](const std::vector<double>& v) -> nlohmann::json {
      double total = 0.0;
      double worst = 0.0;
      for (const double s : v) {
        total += s;
        worst = std::max(worst, s);
      }
      return {{"mean", v.empty() ? 0.0 : total / static_cast<double>(v.size())},
              {"max", worst},
              {"last", v.empty() ? 0.0 : v.back()}};
    };
    return {{"period_s", period_},
            {"count", written_},
            {"key_maps_placed_again", replaced_},
            {"seconds", summary(seconds_)},
            {"cpu_seconds", summary(cpu_seconds_)}};
  }

 private:
  std::filesystem::path dir_;
  double period_;
  fusion::FusionOptions fusion_;
  std::optional<Time> start_;
  long written_ = 0;
  long replaced_ = 0;
  std::vector<double> seconds_;
  std::vector<double> cpu_seconds_;
};

int RunMap(const MapArgs& args, AppContext& context) {
  const auto start = Clock::now();
  const int num_robots = static_cast<int>(args.logs.size());
  std::vector<recording::RecordingReader> readers;
  for (const std::string& log : args.logs) {
    auto reader = recording::RecordingReader::Open(log, context.Recording());
    if (!reader.ok()) {
      return ReportError(reader.error());
    }
    readers.push_back(std::move(reader).value());
  }

  // Held by pointer: released once finished, before the outputs (their images are the largest
  // allocations of a run; the mapper's key maps are no longer needed then).
  auto mapper_holder = std::make_unique<pipeline::Mapper>(context.options.Mapper(), num_robots);
  pipeline::Mapper& mapper = *mapper_holder;
  MapSession session(context.options, args.logs);
  std::vector<pipeline::FrameSource> sources;
  for (recording::RecordingReader& reader : readers) {
    sources.push_back([&reader] { return reader.Next(); });
  }
  auto output = OutputDir::Begin(args.output);  // staged, committed at the end (issue 17)
  if (!output.ok()) {
    return ReportError(output.error());
  }
  // --snapshots: the map every S seconds of log time, written into the staged output (no
  // half-written output on an error).
  const std::filesystem::path partial_dir =
      std::filesystem::path(output.value()->path()) / "snapshots";
  SnapshotWriter snapshots(partial_dir, args.snapshot_period, context.options.fusion);
  std::error_code ec;
  if (args.snapshot_period > 0.0) {
    std::filesystem::create_directories(partial_dir, ec);
    if (ec) {
      return ReportError(
          RuntimeError("cannot create " + partial_dir.string() + ": " + ec.message()));
    }
  }
  const bool progress = isatty(fileno(stderr)) != 0;
  long processed = 0;
  double total_bytes = 0.0;
  for (const recording::RecordingReader& reader : readers) {
    total_bytes += static_cast<double>(reader.TotalBytes());
  }
  auto last_progress = Clock::now();
  std::optional<Error> snapshot_error;
  const Status fed = pipeline::InterleaveFrames(std::move(sources), [&](int robot,
                                                                        const Frame& frame) {
    session.Record(robot, frame);
    mapper.AddFrame(robot, frame);
    if (!snapshot_error) {
      if (const Status s = snapshots.AfterFrame(mapper, frame.time); !s.ok()) {
        snapshot_error = s.error();
      }
    }
    if (progress && ++processed % 50 == 0 &&
        (processed == 50 || Clock::now() - last_progress > std::chrono::milliseconds(500))) {
      last_progress = Clock::now();
      double read = 0.0;
      for (const recording::RecordingReader& reader : readers) {
        read += static_cast<double>(reader.BytesRead());
      }
      PrintProgress(total_bytes > 0.0 ? std::min(1.0, read / total_bytes) : 0.0,
                    std::chrono::duration<double>(last_progress - start).count(), mapper.Stats());
    }
  });
  if (progress) {
    PrintProgress(1.0, std::chrono::duration<double>(Clock::now() - start).count(), mapper.Stats());
    std::fprintf(stderr, "\n");
  }
  if (!fed.ok() || snapshot_error) {
    std::filesystem::remove_all(partial_dir, ec);
    return ReportError(fed.ok() ? *snapshot_error : fed.error());
  }
  std::vector<RobotOutput>& robots = session.Robots();
  for (std::size_t r = 0; r < readers.size(); ++r) {
    robots[r].skipped_malformed = readers[r].Stats().skipped_malformed;
    robots[r].repaired_timestamps = readers[r].Stats().repaired_timestamps;
    if (robots[r].scans == 0) {  // nothing to map: say so, leave any earlier result alone
      return ReportError(io::NoScansError(args.logs[r], readers[r].Stats()));
    }
  }
  const auto mapped = Clock::now();
  const double cpu_caller = ThreadCpuSeconds();
  pipeline::MapperResult result = mapper.Finish();
  mapper_holder.reset();
  ReleaseFreedMemory();
  nlohmann::json rotations = nlohmann::json::array();
  if (args.align_map) {
    const auto occupied =
        static_cast<float>(ProbabilityToLogOdds(context.options.fusion.occupied_probability));
    for (std::size_t c = 0; c < result.maps.size(); ++c) {
      const double angle = DominantWallAngle(result.maps[c], occupied);
      RotateMapFrame(result, static_cast<int>(c), angle, context.options.fusion.margin);
      rotations.push_back(-angle);
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();

  nlohmann::json report = session.Report(result);
  if (args.align_map) {
    report["map_rotation_rad"] = rotations;  // per map: rotation applied to its frame
  }
  if (args.snapshot_period > 0.0) {
    report["snapshots"] = snapshots.Json();
  }
  const double duration = session.Duration();
  report["time_s"]["total"] = seconds;
  report["time_s"]["mapping"] = std::chrono::duration<double>(mapped - start).count();
  report["time_s"]["cpu_caller"] = cpu_caller;
  report["real_time_factor"] = seconds > 0.0 ? duration / seconds : 0.0;
  auto quality_summary = session.Write(output.value()->path(), result, report, "gridslam map");
  if (!quality_summary.ok()) {
    return ReportError(quality_summary.error());
  }
  if (const Status s = output.value()->Commit(); !s.ok()) {
    return ReportError(s.error());
  }
  if (const int removed = RemoveStaleMapOutputs(args.output, robots.size(), result.maps.size());
      removed > 0) {
    std::fprintf(stderr, "gridslam map: removed %d file(s) of an earlier run from %s\n", removed,
                 args.output.c_str());
  }
  const pipeline::MapperStats& s = result.stats;
  // Say what the front end had to do without the odometry (a glitching or missing odometry is
  // otherwise silent).
  if (s.odometry_missing > 0) {
    std::fprintf(stderr,
                 "gridslam map: warning: %ld scans have no odometry; their motion comes from scan "
                 "matching alone\n",
                 s.odometry_missing);
  }
  if (s.odometry_overruled > 0) {
    std::fprintf(stderr,
                 "gridslam map: warning: %ld odometry increments were implausible and replaced by "
                 "scan matching (glitches?)\n",
                 s.odometry_overruled);
  }
  // Where the scans put the laser: a log that lost its mounting gives the laser's poses, not the
  // robot's (docs/frames.md).
  for (std::size_t r = 0; r < result.mountings.size(); ++r) {
    PrintMountingNote("gridslam map", robots[r].log, result.mountings[r],
                      context.options.fusion.resolution);
  }
  std::fprintf(stderr,
               "gridslam map: %ld scans, %ld key maps, %ld loop closures accepted (%ld verified, "
               "%ld gated, %ld pruned), %ld joins; %.2f s, %.0fx real time; outputs in %s\n",
               s.frames, s.key_maps, s.accepted, s.verified, s.rejected_gate, s.pruned, s.joins,
               seconds, seconds > 0.0 ? duration / seconds : 0.0, args.output.c_str());
  if (!quality_summary.value().empty()) {
    std::fprintf(stderr, "gridslam map: %s\n", quality_summary.value().c_str());
  }
  return kExitOk;
}

RunFunction SetupMap(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<MapArgs>();
  sub.add_option(
         "LOG", args->logs,
         "Recording(s), one per robot: CARMEN log (optionally gzip-compressed), ROS 1 .bag, "
         "MCAP .mcap, rosbag2 folder or .db3")
      ->required();
  sub.add_option("-o,--output", args->output, "Output folder")->required()->check(OutputFolder());
  sub.add_flag("--align-map", args->align_map,
               "Rotate the map frame so that the dominant wall directions lie along its axes "
               "(default: the first key map's frame)");
  sub.add_option("--snapshots", args->snapshot_period,
                 "Write the map every S seconds of log time into OUTPUT/snapshots/ (PNG "
                 "flip-book through the online API; 0 = none) [s]")
      ->check(CLI::NonNegativeNumber);
  return [args](AppContext& ctx) { return RunMap(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "map", "The whole system: key maps, SURF on the distance transform, SGD graph, fused map",
    SetupMap});

}  // namespace
}  // namespace gridslam::app
