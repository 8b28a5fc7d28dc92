// Key-map selection (docs/design.md §1.3; docs/method.md §1.4, `checkForKeyMap`): after each
// scan, the rolling window becomes a key map when its origin has moved more than
// `keymap_distance` since the last key map (the origin moves only when the window rolls, so in
// practice one key map per roll), or when `keymap_period` seconds have passed. The builder
// collects the scans in between and hands them to the key map with their poses in its frame.
#pragma once

#include <optional>
#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/grid/rolling_window.hpp"
#include "gridslam/keymap/key_map.hpp"

namespace gridslam::keymap {

struct KeyMapOptions {
  double size = 15.0;  ///< Side of a key map [m]: the centre of the window (cell count odd).
  double keymap_distance = 0.5;  ///< Window-origin travel that triggers a key map [m].
  double keymap_period = 20.0;   ///< Time that triggers a key map [s].
  bool keep_scans = true;        ///< Whether key maps keep the scans' ranges (for fusion).

  template <class V>
  void Visit(V& v) {
    v("size", size,
      "Side of a key map [m]: the central part of the (possibly larger) rolling window");
    v("keymap_distance", keymap_distance,
      "A key map is taken when the window origin moved more than this since the last one [m]");
    v("keymap_period", keymap_period, "... or when this much time passed [s]");
    v("keep_scans", keep_scans, "Key maps keep their scans' ranges (needed to re-insert scans)");
  }
  [[nodiscard]] Status Validate() const;
  /// Cells along a key map's side at `resolution` [m] (odd).
  [[nodiscard]] int NumCells(double resolution) const;
};

class KeyMapBuilder {
 public:
  explicit KeyMapBuilder(const KeyMapOptions& options) : options_(options) {}

  /// Records a scan the front end inserted (or matched) at `T_odom_base`.
  void AddScan(const Frame& frame, const Pose2& T_odom_base);

  /// After the scan was inserted into `window`: a key map if the trigger fires, else nullopt.
  std::optional<KeyMap> MaybeSnapshot(const RollingWindow& window);

  /// A last key map with the scans not yet in one (nullopt if there are none).
  std::optional<KeyMap> Finish(const RollingWindow& window);

  [[nodiscard]] std::size_t NumPendingScans() const { return pending_.size(); }

 private:
  KeyMap Snapshot(const RollingWindow& window);

  struct Pending {
    Time time;
    Pose2 T_odom_base;
    Pose2 T_base_laser;
    LaserScan scan;
  };
  KeyMapOptions options_;
  std::vector<Pending> pending_;
  std::optional<Eigen::Vector2d> last_origin_;  ///< Window origin at the last key map.
  std::optional<Time> last_time_;               ///< Time of the last key map (or first scan).
  int next_id_ = 0;
};

}  // namespace gridslam::keymap
