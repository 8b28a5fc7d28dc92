#include "gridslam/multi_robot/log_split.hpp"

#include <numbers>

#include "gridslam/common/check.hpp"

namespace gridslam::multi_robot {
namespace {

// SplitMix64 (Steele, Lea, Flood 2014): a tiny generator whose output is the same on every
// platform, unlike the std distributions.
std::uint64_t SplitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31U);
}

/// Uniform in [0, 1).
double Uniform(std::uint64_t& state) {
  return static_cast<double>(SplitMix64(state) >> 11U) * 0x1.0p-53;
}

/// First indices of the N cores, plus the log's size at the end.
std::vector<std::size_t> CoreBoundaries(const std::vector<Frame>& frames, int num_pieces,
                                        const std::string& by) {
  const std::size_t n = frames.size();
  const auto pieces = static_cast<std::size_t>(num_pieces);
  std::vector<std::size_t> bounds(pieces + 1, n);
  bounds[0] = 0;
  if (by == "scans") {
    for (std::size_t i = 1; i < pieces; ++i) {
      bounds[i] = i * n / pieces;
    }
    return bounds;
  }
  const Time t0 = frames.front().corrected_time;
  const Duration span = frames.back().corrected_time - t0;
  std::size_t k = 0;
  for (std::size_t i = 1; i < pieces; ++i) {
    const Time t = t0 + Duration(span.count() / num_pieces * static_cast<long>(i));
    while (k < n && frames[k].corrected_time < t) {
      ++k;
    }
    bounds[i] = k;
  }
  return bounds;
}

}  // namespace

Pose2 RandomStart(std::uint64_t seed, int index, double max_translation) {
  std::uint64_t state = seed * 0x2545F4914F6CDD1DULL + static_cast<std::uint64_t>(index) + 1U;
  SplitMix64(state);  // decorrelate neighbouring seeds
  const double x = (2.0 * Uniform(state) - 1.0) * max_translation;
  const double y = (2.0 * Uniform(state) - 1.0) * max_translation;
  const double theta = (2.0 * Uniform(state) - 1.0) * std::numbers::pi;
  return {x, y, theta};
}

Result<SplitPlan> PlanSplit(const std::vector<Frame>& frames, int num_pieces, std::uint64_t seed,
                            const SplitOptions& options) {
  GRIDSLAM_RETURN_IF_ERROR(options.Validate());
  if (num_pieces < 1) {
    return InvalidInput("the number of pieces must be at least 1, not " +
                        std::to_string(num_pieces));
  }
  const auto min_scans = static_cast<std::size_t>(options.min_scans);
  if (frames.size() < static_cast<std::size_t>(num_pieces) * min_scans) {
    return InvalidInput("the log has " + std::to_string(frames.size()) + " scans, too few for " +
                        std::to_string(num_pieces) + " pieces of at least " +
                        std::to_string(min_scans));
  }
  const std::vector<std::size_t> bounds = CoreBoundaries(frames, num_pieces, options.by);
  SplitPlan plan;
  plan.home.assign(frames.size(), 0);
  for (int i = 0; i < num_pieces; ++i) {
    SplitPiece piece;
    piece.core_begin = bounds[static_cast<std::size_t>(i)];
    piece.core_end = bounds[static_cast<std::size_t>(i) + 1];
    if (piece.core_end - piece.core_begin < min_scans) {
      return InvalidInput("piece " + std::to_string(i) + " would hold only " +
                          std::to_string(piece.core_end - piece.core_begin) +
                          " scans (a gap in the log?); fewer pieces or --by scans");
    }
    piece.begin = piece.core_begin;
    piece.end = piece.core_end;
    // The overlap reaches back at most to the previous piece's core start.
    const std::size_t limit = i > 0 ? bounds[static_cast<std::size_t>(i) - 1] : 0;
    const Time start = frames[piece.core_begin].corrected_time;
    while (options.overlap > 0.0 && piece.begin > limit &&
           ToSeconds(start - frames[piece.begin - 1].corrected_time) <= options.overlap) {
      --piece.begin;
    }
    piece.T_new_old =
        RandomStart(seed, i, options.max_translation) * frames[piece.begin].T_odom_base.Inverse();
    for (std::size_t k = piece.core_begin; k < piece.core_end; ++k) {
      plan.home[k] = i;
    }
    plan.pieces.push_back(piece);
  }
  return plan;
}

std::vector<Frame> PieceFrames(const std::vector<Frame>& frames, const SplitPiece& piece) {
  GRIDSLAM_CHECK(piece.begin <= piece.end && piece.end <= frames.size())
      << piece.begin << " " << piece.end << " " << frames.size();
  std::vector<Frame> out(frames.begin() + static_cast<std::ptrdiff_t>(piece.begin),
                         frames.begin() + static_cast<std::ptrdiff_t>(piece.end));
  for (Frame& frame : out) {
    frame.T_odom_base = piece.T_new_old * frame.T_odom_base;
  }
  return out;
}

}  // namespace gridslam::multi_robot
