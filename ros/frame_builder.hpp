// Frames for the mapper from the scans and odometry a ROS graph delivers (C++20 side of the node):
// the same Frame as the bag reader builds from a recording (recording/bag_reader.hpp): the
// LaserScan through recording::MakeLaserScan, range_max capped at log.max_usable_range, the
// mounting from TF unless log.laser_offset overrides it, and the odometry samples (TF or topic)
// interpolated at the scan's stamp (recording::InterpolateOdometry; an odometry ending in an
// intermediate frame completed by its fixed transform, as the bag reader does). Stamps are used as
// they arrive: no timestamp repair (log.repair_timestamps needs a recording's storage order, which
// a live stream lacks).
#pragma once

#include <cstdint>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/io/carmen_options.hpp"
#include "gridslam/recording/odometry_interpolation.hpp"
#include "gridslam/scan/laser_scan.hpp"

#include "live_types.hpp"

namespace gridslam::live {

/// T_parent_child of a 3D transform reduced to the plane (x, y, yaw).
Pose2 PlanarOf(const Transform3D& T_parent_child);
PlanarPose ToPlanar(const Pose2& pose);

class FrameBuilder {
 public:
  FrameBuilder(io::CarmenOptions log, OdometrySource source);

  /// An odometry sample. Samples older than the newest are inserted in stamp order.
  void AddOdometry(const OdometryInput& odometry);
  /// Whether a scan at `stamp_ns` can be built without waiting: the odometry has a sample at or
  /// after it (always true without odometry).
  [[nodiscard]] bool Covers(std::int64_t stamp_ns) const;

  /// The frame of a scan; InvalidInput for an unusable scan (no beams, non-finite geometry, no
  /// odometry sample yet). `clamped`: the odometry was taken from the nearest sample because none
  /// lies on the other side of the stamp.
  Result<Frame> Build(const ScanInput& scan, bool* clamped);

  /// Samples kept for interpolation (old ones are dropped as scans move on).
  [[nodiscard]] std::size_t OdometrySamples() const { return samples_.size(); }

 private:
  io::CarmenOptions log_;
  OdometrySource source_;
  std::vector<recording::OdometrySample> samples_;
  long built_ = 0;
};

}  // namespace gridslam::live
