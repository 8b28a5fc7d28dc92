// Repair of CARMEN timestamps printed without zero padding (docs/formats.md §1.5, intel): a time of
// 976052864.045862 s was printed as "976052864.45862" (the microseconds without their leading
// zero) and read back as .458620. Each printed time therefore stands for one of several
// candidates (its fraction with k of its trailing zeros dropped, read as microseconds). A log with
// this bug never prints a fraction below 0.1 s, while a correct log does so for one time in ten:
// the repairer watches the first `detect_count` times and, if none is below 0.1, picks for the
// stream (all ODOM and laser lines in file order, which is intel's true order) the candidate
// sequence that runs most evenly forward: a Viterbi search whose transition cost is the squared
// forward gap, or a heavy penalty for going backwards, plus a small prior against unpadding, run
// with a fixed lag so memory stays bounded. On intel this repairs about 3 900 lines (a tenth of
// all, as expected) and leaves 1 of 889 inversions; a correct log (fr079, whose
// laser and ODOM lines interleave out of time order) is returned unchanged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "gridslam/common/time.hpp"

namespace gridslam::io {

/// The candidate true times of a printed timestamp: candidates[0] is the printed value; then,
/// when the text has exactly 6 decimals ending in zeros, the fraction with 1, 2, ... trailing
/// zeros removed, read as an unpadded microsecond count.
std::vector<Time> UnpaddedCandidates(std::string_view text, Time printed);

/// True when a printed time has a fraction below 0.1 s (impossible with the unpadding bug).
bool HasSmallFraction(std::string_view text);

/// Fixed-lag Viterbi smoother over one stream of timestamps.
class TimestampRepairer {
 public:
  /// `lag` = entries kept before the oldest is committed; the bug is detected after
  /// `detect_count` entries without a fraction below 0.1 s (or at the end of a stream of at least
  /// `min_count` such entries).
  explicit TimestampRepairer(std::size_t lag = 32, std::size_t detect_count = 100,
                             std::size_t min_count = 20);

  /// Adds the next entry of the stream (in file order): its printed text and parsed value.
  void Push(std::uint64_t id, std::string_view text, Time printed);
  /// True once the stream was found to have unpadded times (repair active).
  [[nodiscard]] bool Repairing() const { return mode_ == Mode::kRepair; }
  /// Commits every pending entry (end of input).
  void Flush();
  /// The next committed (id, repaired time), in push order; nullopt if none is ready.
  std::optional<std::pair<std::uint64_t, Time>> Pop();
  [[nodiscard]] bool HasPending() const { return !pending_.empty() || !undecided_.empty(); }

 private:
  struct Step {
    std::uint64_t id = 0;
    std::vector<Time> candidates;
    std::vector<int> back;  ///< Best predecessor candidate per candidate (-1 for the first).
  };
  enum class Mode { kUndecided, kRepair, kIdentity };
  void AddStep(std::uint64_t id, std::vector<Time> candidates);
  void CommitOldest();
  void Decide(Mode mode);

  std::size_t lag_;
  std::size_t detect_count_;
  std::size_t min_count_;
  Mode mode_ = Mode::kUndecided;
  std::vector<std::pair<std::uint64_t, std::vector<Time>>> undecided_;
  std::deque<Step> pending_;
  std::vector<double> cost_;  ///< Path cost of each candidate of the newest step.
  std::optional<Time> last_committed_;
  std::deque<std::pair<std::uint64_t, Time>> ready_;
};

}  // namespace gridslam::io
