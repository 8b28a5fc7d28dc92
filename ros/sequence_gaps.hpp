// Messages lost before a subscriber saw them (a full queue on the publisher's or the subscriber's
// side), counted from the gaps in header.seq: a publisher numbers its messages 0, 1, 2, ...; a
// number not seen once `window` later ones have arrived is lost. Late arrivals within the window
// (reordered playback) are not; a number far behind the newest starts a new publisher's count.
// Standard library only (the ROS adapter, C++17, uses it).
#pragma once

#include <cstdint>
#include <optional>
#include <set>

namespace gridslam::live {

class SequenceGaps {
 public:
  explicit SequenceGaps(std::uint32_t window = 100) : window_(window) {}

  /// Counts one message; returns how many are known lost so far.
  long Add(std::uint32_t seq);
  [[nodiscard]] long Lost() const { return lost_; }

 private:
  std::uint32_t window_;
  std::optional<std::uint32_t> newest_;
  std::set<std::uint32_t> missing_;  ///< Gaps within the window of the newest.
  long lost_ = 0;
};

}  // namespace gridslam::live
