// Streaming reader of CARMEN laser logs (docs/formats.md §1; docs/design.md §1.1): FLASER, RLASER,
// RAWLASER1..4, ROBOTLASER1, ODOM, PARAM, TRUEPOS and comments, plain or gzip-compressed. Lines
// are read in file order through a bounded look-ahead buffer, so memory does not grow with the
// log length; laser lines without a pose (RAWLASER*) get the odometry interpolated from the ODOM
// lines around them (linear in x, y, shortest arc in theta). Each line keeps its own beam
// geometry (interleaved scanners), and no-return readings (sentinels, > max_usable_range, NaN,
// <= 0) stay in `ranges` but fall outside (range_min, range_max) so LaserScan::IsHit() excludes
// them. A log with pose-less laser lines and no ODOM line at all gives frames with
// has_odometry = false (identity odometry placeholder). A log whose first laser line has no
// timestamp (0, or the field missing) gets times synthesized from message order at
// CarmenOptions::timestamp_rate, with a warning; in such a log, FLASER lines whose odometry
// triple is all zero carry the odometry in their laser triple (orebro). Timestamp quirks (§1.5) are
// repaired in Frame::corrected_time; Frame::time keeps the printed value.
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "gridslam/common/result.hpp"
#include "gridslam/io/carmen_options.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::io {

/// Counts of what a reader saw, for messages and tests.
struct CarmenStats {
  long lines = 0;                   ///< Lines read (all kinds).
  long scans = 0;                   ///< Frames delivered.
  long odometry = 0;                ///< ODOM lines used.
  long comments = 0;                ///< Empty lines and '#' comments.
  long params = 0;                  ///< PARAM lines.
  long truepos = 0;                 ///< TRUEPOS lines.
  long skipped_unknown = 0;         ///< Lines of unknown message types (one warning per type).
  long skipped_malformed = 0;       ///< Malformed lines skipped in lenient mode.
  long skipped_bad_odometry = 0;    ///< ODOM lines with timestamp <= 0.
  long scans_without_odometry = 0;  ///< Pose-less scans outside the ODOM time span (clamped).
  long repaired_timestamps = 0;     ///< Lines whose corrected_time differs from the printed one.
  long synthesized_timestamps = 0;  ///< Lines whose time was synthesized (the log has none).
  std::set<std::string> unknown_types;  ///< Unknown message types seen.
};

namespace internal {
struct CarmenState;
}  // namespace internal

class CarmenReader {
 public:
  /// Opens a log (gzip or plain). NotFound if it cannot be opened.
  static Result<CarmenReader> Open(const std::string& path, const CarmenOptions& options);

  CarmenReader(CarmenReader&&) noexcept;
  CarmenReader& operator=(CarmenReader&&) noexcept;
  ~CarmenReader();

  /// The next laser frame in file order, nullopt at the end of the log, or the first error
  /// (a malformed line of a known type, unless options.lenient).
  Result<std::optional<Frame>> Next();

  [[nodiscard]] const CarmenStats& Stats() const;
  /// Bytes of the file read so far (compressed bytes for a gzip log), for progress reports.
  [[nodiscard]] long BytesRead() const;

 private:
  CarmenReader();
  std::unique_ptr<internal::CarmenState> state_;
};

/// The error for a log that delivered no laser scan (empty, binary, ODOM-only, comments-only or
/// unknown types): InvalidInput naming the file and what it did hold.
Error NoScansError(const std::string& path, const CarmenStats& stats);

/// Every frame of an open `reader` (CarmenReader or any reader with the same Next() and Stats()),
/// and its statistics into `stats` (may be null).
template <class Reader>
Result<std::vector<Frame>> ReadAllFrames(Reader& reader, CarmenStats* stats) {
  std::vector<Frame> frames;
  while (true) {
    auto next = reader.Next();
    if (!next.ok()) {
      return next.error();
    }
    if (!next.value()) {
      break;
    }
    frames.push_back(std::move(*next.value()));
  }
  if (stats != nullptr) {
    *stats = reader.Stats();
  }
  return frames;
}

/// Reads a whole log into memory (convenience for tests and small logs).
Result<std::vector<Frame>> ReadCarmenLog(const std::string& path, const CarmenOptions& options);

/// As above, also returning the statistics.
Result<std::vector<Frame>> ReadCarmenLog(const std::string& path, const CarmenOptions& options,
                                         CarmenStats* stats);

}  // namespace gridslam::io
