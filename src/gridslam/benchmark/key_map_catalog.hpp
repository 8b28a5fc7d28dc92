// What the alignment benchmark (docs/design.md §3.2) needs to know of a front-end run: the front
// end (scan_matching/front_end.hpp) is run over a log's frames and, for every key map, its frame
// T_odom_key, its window in the odometry frame and the range of scans it holds are recorded,
// together with every scan's estimated pose. The key maps themselves are handed to a callback
// and not kept, so a long log costs little memory; the front end is deterministic, so a second
// run hands out the same key maps again. The scan at time t belongs to the key map that holds it;
// the robot's pose in that key map's frame is T_key_base(t) = T_odom_key^-1 * T_odom_base(t),
// which is accurate because the front end is locally consistent.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/time.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/keymap/key_map.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/scan_matching/front_end_options.hpp"

namespace gridslam::benchmark {

/// One key map of a front-end run.
struct KeyMapRecord {
  int id = 0;
  Pose2 T_odom_key;  ///< Key-map frame (window centre, yaw 0) in the front end's frame.
  Eigen::Vector2d window_min = Eigen::Vector2d::Zero();  ///< Window corners, odometry frame [m].
  Eigen::Vector2d window_max = Eigen::Vector2d::Zero();
  int first_frame = 0;  ///< Index of the first scan it holds.
  int last_frame = 0;   ///< Index of the last scan it holds.
  double travel = 0.0;  ///< Path length driven up to its last scan [m].
};

/// One scan of a front-end run.
struct FrameRecord {
  Time time;            ///< Printed timestamp.
  Pose2 T_odom_base;    ///< Front-end estimate.
  Pose2 T_base_laser;   ///< Laser mounting.
  int key_map = -1;     ///< Key map holding the scan.
  double travel = 0.0;  ///< Path length driven up to this scan [m].
};

class KeyMapCatalog {
 public:
  using KeyMapCallback = std::function<void(keymap::KeyMap&&)>;

  /// Runs a front end with `options` over `frames` (log order) and records it; every finished
  /// key map (including the last, from FrontEnd::Finish) is passed to `on_key_map` if set.
  /// Contract: options valid.
  static KeyMapCatalog Build(std::span<const Frame> frames,
                             const scan_matching::FrontEndOptions& options,
                             const KeyMapCallback& on_key_map = {});

  [[nodiscard]] const std::vector<KeyMapRecord>& KeyMaps() const { return key_maps_; }
  [[nodiscard]] const std::vector<FrameRecord>& Frames() const { return frames_; }
  /// Wall time of the front-end run [s].
  [[nodiscard]] double Seconds() const { return seconds_; }

  /// Index of the scan whose timestamp is nearest to `time`, or -1 if none is within
  /// `tolerance` [s].
  [[nodiscard]] int FindFrame(Time time, double tolerance) const;

  /// Pose of the robot (laser if `laser`) at scan `frame` in the frame of the key map holding it.
  [[nodiscard]] Pose2 PoseInKeyMap(int frame, bool laser) const;

  /// Whether the local map forgot everything between key maps `a` and `b`: the windows of the
  /// key maps from a to b have no point in common, so no cell of a's map survived into b's.
  /// (Windows between two key maps are not recorded, so a few such pairs count as not separated.)
  [[nodiscard]] bool WindowsSeparated(int a, int b) const;

 private:
  std::vector<KeyMapRecord> key_maps_;
  std::vector<FrameRecord> frames_;
  std::vector<int> by_time_;  ///< Frame indices sorted by time.
  double seconds_ = 0.0;
};

}  // namespace gridslam::benchmark
