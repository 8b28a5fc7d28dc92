#include "mapping_core.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/io/map_io.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/slam_options.hpp"

#include "app_map_session.hpp"
#include "app_output_dir.hpp"
#include "frame_builder.hpp"

namespace gridslam::live {
namespace {

using SteadyClock = std::chrono::steady_clock;

GridOutput ToGridOutput(const OccupancyImage& image, std::int64_t stamp_ns) {
  GridOutput grid;
  grid.stamp_ns = stamp_ns;
  grid.width = image.Width();
  grid.height = image.Height();
  grid.resolution = image.Limits().Resolution();
  grid.origin_x = image.Limits().Origin().x();
  grid.origin_y = image.Limits().Origin().y();
  grid.cells.assign(image.Cells().begin(), image.Cells().end());
  return grid;
}

std::vector<StampedPose> ToPath(const std::vector<pipeline::TrajectoryPose>& trajectory) {
  std::vector<StampedPose> path;
  path.reserve(trajectory.size());
  for (const pipeline::TrajectoryPose& p : trajectory) {
    path.push_back({p.time.time_since_epoch().count(), ToPlanar(p.T_map_base)});
  }
  return path;
}

std::string OdometryName(OdometrySource source) {
  switch (source) {
    case OdometrySource::kTf:
      return "tf";
    case OdometrySource::kTopic:
      return "topic";
    case OdometrySource::kNone:
      return "none";
  }
  return "?";
}

}  // namespace

void LogToStderr() {
  spdlog::set_default_logger(spdlog::stderr_color_mt("gridslam"));
  spdlog::set_pattern("[gridslam] [%l] %v");
}

struct MappingCore::Impl {
  Impl(const CoreSettings& s, CoreCallbacks c, const SlamOptions& o)
      : settings(s),
        callbacks(std::move(c)),
        options(o),
        builder(o.log, s.odometry),
        mapper(o.Mapper(), 1),
        session(o, {s.session_name}) {}

  struct Pending {
    ScanInput scan;
    SteadyClock::time_point received;
  };

  void Run();
  void Map(const Frame& frame);
  /// The latest map: the final one after Finish, else a snapshot. Empty before the first key map.
  OccupancyImage CurrentMap();

  const CoreSettings settings;
  const CoreCallbacks callbacks;
  const SlamOptions options;

  // The queue and the odometry (queue_mutex).
  std::mutex queue_mutex;
  std::condition_variable queue_changed;
  std::deque<Pending> queue;
  FrameBuilder builder;
  bool stop = false;
  bool finishing = false;  ///< No more scans taken; queued ones do not wait for odometry.
  bool busy = false;       ///< The core thread is mapping a scan taken from the queue.

  // The mapper and what it produced (mapper_mutex).
  std::mutex mapper_mutex;
  pipeline::Mapper mapper;
  app::MapSession session;
  std::optional<pipeline::MapperResult> result;
  std::optional<std::int64_t> last_map_stamp;

  // The latest pose (pose_mutex: read by the periodic TF publisher without waiting for mapping).
  mutable std::mutex pose_mutex;
  std::optional<PlanarPose> latest_pose;

  std::atomic<long> received{0};
  std::atomic<long> mapped{0};
  std::atomic<long> dropped{0};
  std::atomic<long> clamped{0};
  std::atomic<long> key_maps{0};
  std::atomic<long> closures{0};
  std::atomic<long> maps_published{0};
  std::atomic<bool> finished{false};

  std::thread thread;  // last: started when everything above exists
};

void MappingCore::Impl::Run() {
  std::unique_lock<std::mutex> lock(queue_mutex);
  while (true) {
    queue_changed.wait(lock, [this] { return stop || !queue.empty(); });
    if (stop) {
      return;
    }
    const Pending& next = queue.front();
    if (!finishing && !builder.Covers(next.scan.stamp_ns)) {
      const auto deadline = next.received + std::chrono::duration_cast<SteadyClock::duration>(
                                                std::chrono::duration<double>(settings.odom_wait));
      if (SteadyClock::now() < deadline) {
        queue_changed.wait_until(lock, deadline);
        continue;
      }
    }
    const Pending pending = std::move(queue.front());
    queue.pop_front();
    bool outside = false;
    auto frame = builder.Build(pending.scan, &outside);
    busy = true;
    lock.unlock();
    if (frame.ok()) {
      clamped += outside ? 1 : 0;
      Map(frame.value());
    } else {
      ++dropped;
      spdlog::warn("gridslam_node: scan at {} dropped: {}",
                   FormatSeconds(Time(Duration(pending.scan.stamp_ns)), 6), frame.error().message);
    }
    lock.lock();
    busy = false;
    queue_changed.notify_all();
  }
}

void MappingCore::Impl::Map(const Frame& frame) {
  const std::int64_t stamp = frame.time.time_since_epoch().count();
  PlanarPose pose;
  std::optional<GridOutput> grid;
  std::vector<StampedPose> path;
  {
    const std::lock_guard<std::mutex> lock(mapper_mutex);
    session.Record(0, frame);
    mapper.AddFrame(0, frame);
    mapper.DrainEvents();  // not used: the statistics say the same
    pose = ToPlanar(settings.odometry == OdometrySource::kNone ? mapper.CurrentPose(0).value()
                                                               : mapper.MapToOdom(0));
    key_maps = mapper.Stats().key_maps;
    closures = mapper.Stats().accepted;
    const bool due = settings.map_publish_period > 0.0 &&
                     (!last_map_stamp || static_cast<double>(stamp - *last_map_stamp) >=
                                             1e9 * settings.map_publish_period);
    if (due && callbacks.on_map) {
      pipeline::MapSnapshot snapshot = mapper.Snapshot();
      const auto c = static_cast<std::size_t>(snapshot.component_of_robot[0]);
      if (c < snapshot.maps.size() && snapshot.maps[c].size() > 0) {
        grid = ToGridOutput(fusion::ToOccupancy(snapshot.maps[c], options.fusion), stamp);
        path = ToPath(snapshot.trajectories[0]);
        last_map_stamp = stamp;
      }
    }
  }
  {
    const std::lock_guard<std::mutex> lock(pose_mutex);
    latest_pose = pose;
  }
  ++mapped;
  if (callbacks.on_pose) {
    callbacks.on_pose(stamp, pose);
  }
  if (grid) {
    ++maps_published;
    callbacks.on_map(*grid, path);
  }
}

OccupancyImage MappingCore::Impl::CurrentMap() {
  const std::lock_guard<std::mutex> lock(mapper_mutex);
  if (result) {
    const auto c = static_cast<std::size_t>(result->component_of_robot[0]);
    return fusion::ToOccupancy(result->maps[c], options.fusion);
  }
  pipeline::MapSnapshot snapshot = mapper.Snapshot();
  const auto c = static_cast<std::size_t>(snapshot.component_of_robot[0]);
  if (c >= snapshot.maps.size() || snapshot.maps[c].size() == 0) {
    return {};
  }
  return fusion::ToOccupancy(snapshot.maps[c], options.fusion);
}

std::unique_ptr<MappingCore> MappingCore::Create(const CoreSettings& settings,
                                                 CoreCallbacks callbacks, std::string* error) {
  SlamOptions options;
  if (!settings.config_path.empty()) {
    if (const Status s = io::LoadOptionsFromFile(settings.config_path, options); !s.ok()) {
      *error = s.error().ToString();
      return nullptr;
    }
  }
  for (const std::string& assignment : settings.overrides) {
    if (const Status s = io::ApplyOptionOverride(assignment, options); !s.ok()) {
      *error = s.error().ToString();
      return nullptr;
    }
  }
  if (const Status s = options.Validate(); !s.ok()) {
    *error = s.error().ToString();
    return nullptr;
  }
  auto impl = std::make_unique<Impl>(settings, std::move(callbacks), options);
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] { raw->Run(); });
  return std::unique_ptr<MappingCore>(new MappingCore(std::move(impl)));
}

MappingCore::MappingCore(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

MappingCore::~MappingCore() {
  {
    const std::lock_guard<std::mutex> lock(impl_->queue_mutex);
    impl_->stop = true;
  }
  impl_->queue_changed.notify_all();
  impl_->thread.join();
}

void MappingCore::AddScan(ScanInput scan) {
  ++impl_->received;
  {
    const std::lock_guard<std::mutex> lock(impl_->queue_mutex);
    if (impl_->finishing) {
      ++impl_->dropped;
      return;
    }
    impl_->queue.push_back({std::move(scan), SteadyClock::now()});
  }
  impl_->queue_changed.notify_all();
}

void MappingCore::AddOdometry(const OdometryInput& odometry) {
  {
    const std::lock_guard<std::mutex> lock(impl_->queue_mutex);
    impl_->builder.AddOdometry(odometry);
  }
  impl_->queue_changed.notify_all();
}

bool MappingCore::LatestPose(PlanarPose* T_map_odom) const {
  const std::lock_guard<std::mutex> lock(impl_->pose_mutex);
  if (!impl_->latest_pose) {
    return false;
  }
  *T_map_odom = *impl_->latest_pose;
  return true;
}

CoreProgress MappingCore::Progress() const {
  CoreProgress s;
  s.scans_received = impl_->received;
  s.scans_mapped = impl_->mapped;
  s.scans_dropped = impl_->dropped;
  s.scans_without_odometry = impl_->clamped;
  {
    const std::lock_guard<std::mutex> lock(impl_->queue_mutex);
    s.scans_queued = static_cast<long>(impl_->queue.size());
  }
  s.key_maps = impl_->key_maps;
  s.loop_closures = impl_->closures;
  s.maps_published = impl_->maps_published;
  s.finished = impl_->finished;
  return s;
}

bool MappingCore::SaveMap(const std::string& dir, std::string* message) {
  const OccupancyImage image = impl_->CurrentMap();
  if (image.size() == 0) {
    *message = "no map yet (the first key map is not complete)";
    return false;
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path yaml = std::filesystem::path(dir) / "map.yaml";
  if (const Status s = io::WriteMap(yaml.string(), "map.pgm", image); !s.ok()) {
    *message = s.error().ToString();
    return false;
  }
  *message = "wrote " + yaml.string() + " and map.pgm (" + std::to_string(image.Width()) + " x " +
             std::to_string(image.Height()) + " cells)";
  return true;
}

bool MappingCore::Finish(const std::string& dir, std::string* message) {
  Impl& d = *impl_;
  {
    std::unique_lock<std::mutex> lock(d.queue_mutex);
    d.finishing = true;
    d.queue_changed.notify_all();
    d.queue_changed.wait(lock, [&d] { return d.queue.empty() && !d.busy; });
  }
  GridOutput grid;
  std::vector<StampedPose> path;
  PlanarPose pose;
  std::string written;
  {
    const std::lock_guard<std::mutex> lock(d.mapper_mutex);
    if (d.session.Robots()[0].scans == 0) {
      *message = "no scan was mapped yet: nothing to write (the session goes on)";
      const std::lock_guard<std::mutex> queue_lock(d.queue_mutex);
      d.finishing = false;
      return false;
    }
    if (!d.result) {
      d.result = d.mapper.Finish();
    }
    const pipeline::MapperResult& result = *d.result;
    const auto c = static_cast<std::size_t>(result.component_of_robot[0]);
    const std::int64_t stamp = result.trajectories[0].back().time.time_since_epoch().count();
    grid = ToGridOutput(fusion::ToOccupancy(result.maps[c], d.options.fusion), stamp);
    path = ToPath(result.trajectories[0]);
    pose = ToPlanar(d.settings.odometry == OdometrySource::kNone ? d.mapper.CurrentPose(0).value()
                                                                 : d.mapper.MapToOdom(0));
    nlohmann::json report = d.session.Report(result);
    report["node"] = {{"odometry", OdometryName(d.settings.odometry)},
                      {"scans_received", d.received.load()},
                      {"scans_dropped", d.dropped.load()},
                      {"scans_with_clamped_odometry", d.clamped.load()},
                      {"maps_published", d.maps_published.load()}};
    auto output = app::OutputDir::Begin(dir);
    if (!output.ok()) {
      *message = output.error().ToString();
      return false;
    }
    auto summary = d.session.Write(output.value()->path(), result, report, "gridslam_node");
    if (!summary.ok()) {
      *message = summary.error().ToString();
      return false;
    }
    if (const Status s = output.value()->Commit(); !s.ok()) {
      *message = s.error().ToString();
      return false;
    }
    app::RemoveStaleMapOutputs(dir, 1, result.maps.size());
    written = summary.value();
    d.finished = true;
  }
  {
    const std::lock_guard<std::mutex> lock(d.pose_mutex);
    d.latest_pose = pose;
  }
  if (d.callbacks.on_map) {
    ++d.maps_published;
    d.callbacks.on_map(grid, path);
  }
  *message = "wrote the session's outputs into " + dir + (written.empty() ? "" : "; " + written);
  return true;
}

}  // namespace gridslam::live
