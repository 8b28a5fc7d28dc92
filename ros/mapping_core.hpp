// The mapping core of gridslam_node (docs/ros.md "Mapping live"): pipeline::Mapper's online API
// (docs/online_api.md) behind plain structs (live_types.hpp), so that the ROS adapter never sees
// gridslam and gridslam never sees ROS. Scans are queued and mapped in order on the core's own
// thread, where a scan waits (at most `odom_wait` of wall time) until an odometry sample (TF or
// topic) at or after its stamp has arrived; its odometry is then interpolated as the bag reader
// does (recording/odometry_interpolation.hpp), so that the node maps what `gridslam map` maps.
// After each scan the core reports map -> odom; every `map_publish_period` of scan time it takes a
// Snapshot and reports the map and the corrected trajectory. SaveMap and Finish write the same
// files as `gridslam map` (apps/, MapSession). Every method may be called from any thread: the
// Mapper is guarded by one mutex.
//
// Standard library only in this header (it is compiled as C++17 by the adapter).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "live_types.hpp"

namespace gridslam::live {

struct CoreSettings {
  std::string config_path;             ///< gridslam YAML ("" = the defaults).
  std::vector<std::string> overrides;  ///< "section.key=value", applied after the file.
  OdometrySource odometry = OdometrySource::kTf;
  double odom_wait = 0.5;  ///< Longest wait of a scan for an odometry sample after it [s, wall].
  double map_publish_period = 5.0;  ///< Map snapshot period in scan time [s]; <= 0: never.
  std::string session_name = "gridslam_node";  ///< The "log" of report.json.
};

struct CoreCallbacks {
  /// After each mapped scan (core thread): the transform to publish at the scan's stamp,
  /// map -> odom (OdometrySource::kNone: map -> base).
  std::function<void(std::int64_t stamp_ns, const PlanarPose& T_map_odom)> on_pose;
  /// A new map and the corrected trajectory so far (core thread, or Finish's caller).
  std::function<void(const GridOutput& map, const std::vector<StampedPose>& path)> on_map;
};

/// Sends gridslam's own log messages to stderr, beside ROS's (call once, first).
void LogToStderr();

class MappingCore {
 public:
  /// Reads and validates the configuration; nullptr with `error` set on failure.
  static std::unique_ptr<MappingCore> Create(const CoreSettings& settings, CoreCallbacks callbacks,
                                             std::string* error);
  ~MappingCore();
  MappingCore(const MappingCore&) = delete;
  MappingCore& operator=(const MappingCore&) = delete;
  MappingCore(MappingCore&&) = delete;
  MappingCore& operator=(MappingCore&&) = delete;

  /// Queues a scan (ignored after Finish).
  void AddScan(ScanInput scan);
  /// Adds an odometry sample (TF or topic; any order).
  void AddOdometry(const OdometryInput& odometry);

  /// The latest transform reported by on_pose; false before the first mapped scan.
  bool LatestPose(PlanarPose* T_map_odom) const;
  [[nodiscard]] CoreProgress Progress() const;

  /// Writes the current map (the final one after Finish) as map.pgm + map.yaml into `dir`
  /// (created if missing). `message` says what was written or what failed.
  bool SaveMap(const std::string& dir, std::string* message);
  /// Maps every queued scan, ends the session (Mapper::Finish), reports the final map and writes
  /// every output of `gridslam map -o DIR` into `dir`. Later scans are ignored; a second call
  /// writes the same result again.
  bool Finish(const std::string& dir, std::string* message);

 private:
  struct Impl;
  explicit MappingCore(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gridslam::live
