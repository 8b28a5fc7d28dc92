// Cutting one robot's log into N robots with unknown relative starts (issue 8; docs/design.md §1.9,
// §2 `gridslam split`): the log's frames are cut into N consecutive pieces (by scan count or by
// time), and each piece is re-expressed in its own odometry frame by a random rigid transform
// T_new_old (any rotation, a translation of up to `max_translation`), drawn from the seed, so
// that the piece's first odometry pose becomes an arbitrary pose. The mapper must then find the
// pieces' relative poses itself (Howard et al. 2006's manifold view: one robot, N unknown
// starts). With an overlap, piece i > 0 starts `overlap` seconds before its core: its robot
// drives the end of the previous piece again, so consecutive robots share a stretch of route.
// Every scan has one home piece, the one whose core (the pieces without overlap, a partition of
// the log) holds it; the home decides how relations and scans are attributed (relation_split.hpp,
// robot_index.hpp). Deterministic for a seed, with a portable generator (no std distributions).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::multi_robot {

struct SplitOptions {
  /// How the log is cut: "scans" (equal scan counts) or "time" (equal durations).
  std::string by = "scans";
  /// Seconds that consecutive pieces share: piece i > 0 also holds the last `overlap` seconds of
  /// piece i - 1's core [s].
  double overlap = 0.0;
  /// Translation of each piece's start: x and y uniform in [-max_translation, max_translation]
  /// [m]; the rotation is uniform in [-pi, pi).
  double max_translation = 50.0;
  /// Fewest scans in a piece's core [-].
  int min_scans = 10;

  template <class V>
  void Visit(V& v) {
    v("by", by, "Cut the log into equal scan counts (scans) or equal durations (time)");
    v("overlap", overlap, "Seconds shared by consecutive pieces [s]");
    v("max_translation", max_translation,
      "Each piece's start: x, y uniform within +-max_translation [m], any rotation");
    v("min_scans", min_scans, "Fewest scans in a piece (without overlap) [-]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(by == "scans" || by == "time", "split.by is scans or time"));
    GRIDSLAM_RETURN_IF_ERROR(Require(overlap >= 0.0, "split.overlap >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_translation >= 0.0 && max_translation <= 1e4,
                                     "split.max_translation in [0, 1e4] m (--max-offset)"));
    GRIDSLAM_RETURN_IF_ERROR(Require(min_scans >= 1, "split.min_scans >= 1"));
    return Status::Ok();
  }
};

/// One piece: frames [begin, end) of the log (file order), of which [core_begin, core_end) are
/// its home scans; begin <= core_begin < core_end == end.
struct SplitPiece {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t core_begin = 0;
  std::size_t core_end = 0;
  Pose2 T_new_old;  ///< Maps the log's odometry frame into the piece's odometry frame.
};

struct SplitPlan {
  std::vector<SplitPiece> pieces;
  std::vector<int> home;  ///< Home piece of every frame of the log.
};

/// Plans the cut of `frames` (a log in file order) into `num_pieces` pieces, with random starts
/// from `seed`. Times are the frames' corrected (repaired) times. InvalidInput when the options
/// are invalid, num_pieces < 1, or a piece would get fewer than options.min_scans scans.
Result<SplitPlan> PlanSplit(const std::vector<Frame>& frames, int num_pieces, std::uint64_t seed,
                            const SplitOptions& options);

/// The frames of `piece`, their odometry (and nothing else) mapped by piece.T_new_old:
/// T_odom_base' = T_new_old * T_odom_base. Times, scans and mountings are unchanged.
std::vector<Frame> PieceFrames(const std::vector<Frame>& frames, const SplitPiece& piece);

/// The random start pose of piece `index` for `seed`: x, y uniform in +-max_translation, theta
/// uniform in [-pi, pi). Each piece draws from its own stream, so a piece's start does not
/// depend on how many pieces there are.
Pose2 RandomStart(std::uint64_t seed, int index, double max_translation);

}  // namespace gridslam::multi_robot
