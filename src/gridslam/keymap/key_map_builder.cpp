#include "gridslam/keymap/key_map_builder.hpp"

#include <cmath>

namespace gridslam::keymap {

int KeyMapOptions::NumCells(double resolution) const {
  const auto n = static_cast<int>(std::lround(size / resolution));
  return n % 2 == 0 ? n + 1 : n;
}

Status KeyMapOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(size > 0.0, "keymap.size > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(keymap_distance > 0.0, "keymap.keymap_distance > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(keymap_period > 0.0, "keymap.keymap_period > 0"));
  return Status::Ok();
}

void KeyMapBuilder::AddScan(const Frame& frame, const Pose2& T_odom_base) {
  Pending p{frame.time, T_odom_base, frame.T_base_laser, {}};
  if (options_.keep_scans) {
    p.scan = frame.scan;
  }
  if (!last_time_) {
    last_time_ = frame.time;
  }
  pending_.push_back(std::move(p));
}

std::optional<KeyMap> KeyMapBuilder::MaybeSnapshot(const RollingWindow& window) {
  if (pending_.empty()) {
    return std::nullopt;
  }
  if (!last_origin_) {
    last_origin_ = window.Limits().Origin();  // the first window is the reference
  }
  const bool moved = (window.Limits().Origin() - *last_origin_).norm() > options_.keymap_distance;
  const bool waited = ToSeconds(pending_.back().time - *last_time_) > options_.keymap_period;
  if (!moved && !waited) {
    return std::nullopt;
  }
  return Snapshot(window);
}

std::optional<KeyMap> KeyMapBuilder::Finish(const RollingWindow& window) {
  if (pending_.empty()) {
    return std::nullopt;
  }
  return Snapshot(window);
}

KeyMap KeyMapBuilder::Snapshot(const RollingWindow& window) {
  KeyMap key;
  key.id = next_id_++;
  key.time = pending_.back().time;
  key.T_odom_key = Pose2(window.Centre(), 0.0);
  key.log_odds = window.SnapshotInCentreFrame(options_.NumCells(window.Limits().Resolution()));
  const Pose2 T_key_odom = key.T_odom_key.Inverse();
  key.scans.reserve(pending_.size());
  for (Pending& p : pending_) {
    key.scans.push_back({p.time, T_key_odom * p.T_odom_base, p.T_base_laser, std::move(p.scan)});
  }
  pending_.clear();
  last_origin_ = window.Limits().Origin();
  last_time_ = key.time;
  return key;
}

}  // namespace gridslam::keymap
