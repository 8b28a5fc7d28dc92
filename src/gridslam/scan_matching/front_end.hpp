// The front end (docs/design.md §1.2-1.3; docs/method.md §1.4): frames go in one at a time; each
// scan is matched against the rolling local map built from the previous scans (scan_matcher.hpp),
// starting from the odometry increment applied to the previous estimate; the scan is then
// inserted at its estimated pose (when the robot moved enough since the last insertion), the
// window rolls with the robot, and a key map is handed out whenever the window's origin moved
// more than keymap_distance (or keymap_period passed). Scans with too few returns, an empty map
// or a rejected match keep the odometry prediction (counted). One code path serves online use
// (call AddFrame per scan) and batch runs (loop, then Finish()).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "gridslam/grid/rolling_window.hpp"
#include "gridslam/keymap/key_map_builder.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/scan_matching/front_end_options.hpp"
#include "gridslam/scan_matching/laser_noise_monitor.hpp"
#include "gridslam/scan_matching/match_score_monitor.hpp"
#include "gridslam/scan_matching/matching_field.hpp"
#include "gridslam/scan_matching/motion_check.hpp"
#include "gridslam/scan_matching/mounting_estimate.hpp"
#include "gridslam/scan_matching/odometry_noise.hpp"
#include "gridslam/scan_matching/scan_matcher.hpp"

namespace gridslam::scan_matching {

/// How a frame's pose was obtained.
enum class FrameStatus {
  kFirst,              ///< First frame: the odometry pose defines the front end's frame.
  kMatched,            ///< Scan matched.
  kOdometryOnly,       ///< Matching disabled (options.match = false).
  kFallbackFewPoints,  ///< Too few returns to match: odometry prediction.
  kFallbackEmptyMap,   ///< The map had too few obstacles: odometry prediction.
  kFallbackRejected,   ///< The match failed or moved too far: odometry prediction.
};

const char* ToString(FrameStatus status);

/// What happened to one frame.
struct FrontEndStep {
  Time time;          ///< The frame's printed timestamp.
  Pose2 T_odom_base;  ///< Estimated robot pose in the front end's (odometry) frame.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< Of the match, if matched.
  FrameStatus status = FrameStatus::kFirst;
  OdometryCheck odometry = OdometryCheck::kConsistent;  ///< Verdict on the odometry increment.
  bool wide_search = false;  ///< The wide search ran (doubtful or missing odometry).
  /// The scan overruled the odometry increment: a doubtful one, or one whose match was poor and
  /// whose wide search found a clearly better, unambiguous pose (`rescue`).
  bool odometry_overruled = false;
  bool poor_match = false;    ///< The match with odometry was poor (the wide search ran).
  bool wall_normals = false;  ///< The degeneracy test used the wall normals (a noisy laser).
  RescueVerdict rescue = RescueVerdict::kNone;  ///< What the wide search after it concluded.
  MatchResult match;                            ///< Details of the match (if one was attempted).
  bool inserted = false;                        ///< The scan was inserted into the local map.
  std::optional<keymap::KeyMap> key_map;        ///< A key map finished after this frame.
};

/// Counters and time per stage [s] (steady clock).
struct FrontEndStats {
  long frames = 0;
  long matched = 0;
  long fallback_few_points = 0;
  long fallback_empty_map = 0;
  long fallback_rejected = 0;
  long searches = 0;
  long odometry_doubtful = 0;  ///< Increments the motion check found implausible.
  long odometry_missing = 0;   ///< Frames without odometry.
  long wide_searches = 0;
  long odometry_overruled = 0;  ///< Increments the scan match replaced (doubtful or poor).
  long poor_matches = 0;        ///< Matches with odometry found poor (wide search ran).
  long poor_rescued = 0;        ///< ... of which the wide search overruled the odometry.
  long poor_ambiguous = 0;      ///< ... of which a distinct pose scored about as well (kept).
  /// Matched frames whose scan left one / both translation directions to the prior.
  long degenerate_one = 0;
  long degenerate_both = 0;
  /// Matches taken from the matching window, larger than the key-map window (local_map).
  long far_matches = 0;
  /// Frames whose degeneracy test used the wall normals (the laser measured noisy).
  long wall_normal_frames = 0;
  long insertions = 0;
  long key_maps = 0;
  long field_rebuilds = 0;  ///< Distance-field rebuilds and region updates, both windows' fields.
  long field_tile_updates = 0;
  double seconds_preprocess = 0.0;
  double seconds_field = 0.0;
  double seconds_match = 0.0;
  double seconds_insert = 0.0;
  double seconds_keymap = 0.0;
};

class FrontEnd {
 public:
  /// `options` must be valid (Validate()).
  explicit FrontEnd(const FrontEndOptions& options);
  ~FrontEnd();
  FrontEnd(const FrontEnd&) = delete;
  FrontEnd& operator=(const FrontEnd&) = delete;

  /// Processes the next frame (frames in the log's order).
  FrontEndStep AddFrame(const Frame& frame);

  /// The last key map holding the scans not yet in one (nullopt if none); call once at the end.
  std::optional<keymap::KeyMap> Finish();

  [[nodiscard]] const FrontEndStats& Stats() const { return stats_; }
  /// Where the scans put the laser beyond the mounting the frames gave (mounting_estimate.hpp),
  /// from the increments so far: reported, never applied.
  [[nodiscard]] MountingResult Mounting() const { return mounting_.Estimate(); }
  /// The local map the key maps are cut from (null before the first frame).
  [[nodiscard]] const RollingWindow* Window() const { return window_.get(); }
  /// The local map scans are matched against: a larger window than Window() when
  /// local_map.MatchingSize() exceeds local_map.size, Window() itself otherwise (null before the
  /// first frame). Without odometry, a match tries Window() first (MatchInWindows).
  [[nodiscard]] const RollingWindow* MatchingWindow() const {
    return matching_window_ != nullptr ? matching_window_.get() : window_.get();
  }
  [[nodiscard]] const FrontEndOptions& Options() const { return options_; }

 private:
  /// Default standard deviations of the odometry prediction over `odometry_increment`.
  struct PriorSigmas {
    double forward = 0.0;  ///< [m]
    double lateral = 0.0;  ///< [m]
    double theta = 0.0;    ///< [rad]
  };
  [[nodiscard]] PriorSigmas DefaultPriorSigmas(const Pose2& odometry_increment) const;
  /// The prior's information: the defaults scaled by the odometry noise estimate.
  [[nodiscard]] Eigen::Matrix3d PriorInformation(const PriorSigmas& defaults,
                                                 const Pose2& T_odom_base_predicted,
                                                 bool odometry_trusted) const;
  [[nodiscard]] bool ShouldInsert(const Frame& frame, const Pose2& pose) const;
  /// field_, brought up to date with window_ first. Only matches in window_ read it (without a
  /// separate matching window, or without odometry), so it follows the window's changes when one
  /// does, as matching_field_ does: one update over several scans' changes gives the same
  /// distances as one per scan (a label may name another obstacle at the same distance; the
  /// distance-field residual reads only the distances, and without a separate matching window,
  /// where point_to_line reads the labels, the updates come at the same frames as before).
  [[nodiscard]] const MatchingField& NearField();
  /// Which local map a match uses.
  enum class WindowPolicy {
    /// The matching window, every return inserted: where a measured prior holds the match near
    /// the right pose, the far returns only add constraints.
    kMatchingWindow,
    /// The key-map window first, the matching window only where that match fails or leaves a
    /// direction to the prior: without odometry the match must find the pose by itself, and the
    /// far, older part of the map offers it wrong basins (intel without odometry: 0.96 m against
    /// the matching window, 0.023 m this way).
    kNearFirst,
  };
  /// Matches `points` (Match from `prior`, or Refine from `start` when `refine_only`) in the
  /// windows `policy` names; Window() alone when there is no separate matching window.
  [[nodiscard]] MatchResult MatchInWindows(const ScanPoints& points, const Pose2& start,
                                           const Pose2& prior, const Eigen::Matrix3d& information,
                                           PriorKind kind, bool refine_only, WindowPolicy policy);
  /// Matches a frame whose odometry is doubtful or missing. Doubtful: from the odometry's
  /// prediction and from the constant velocity; the odometry keeps the frame unless the scan
  /// clearly prefers the other pose (`velocity_preferred`). Missing: from the constant velocity,
  /// and from the wide search's maxima when that explains the scan poorly.
  [[nodiscard]] MatchResult MatchWithoutTrustedOdometry(const ScanPoints& points,
                                                        const MotionPrediction& prediction,
                                                        const Eigen::Matrix3d& velocity_information,
                                                        const Eigen::Matrix3d& odometry_information,
                                                        FrontEndStep* step,
                                                        bool* velocity_preferred);
  /// The wide search around `centre` in the windows `policy` names: the lattice's maxima,
  /// refined with `information` as the prior (kMotionModel, moved with each start); the
  /// successful refinements, and the separation beyond which two poses are distinct.
  struct WideRefinements {
    std::vector<MatchResult> matches;
    double separation_xy = 0.0;     ///< [m]
    double separation_theta = 0.0;  ///< [rad]
  };
  [[nodiscard]] WideRefinements WideSearch(const ScanPoints& points, const Pose2& centre,
                                           const Eigen::Matrix3d& information, WindowPolicy policy,
                                           FrontEndStep* step);
  /// After the `poor` match of a frame with odometry: the wide search around the odometry's
  /// prediction, judged by MatchScoreMonitor::Choose (step->rescue); the rescued pose, or `poor`.
  [[nodiscard]] MatchResult RescuePoorMatch(const ScanPoints& points, const Pose2& predicted,
                                            const Eigen::Matrix3d& information,
                                            const MatchResult& poor, FrontEndStep* step);

  FrontEndOptions options_;
  ScanMatcher matcher_;
  std::unique_ptr<RollingWindow> window_;           ///< Key maps are its centre.
  std::unique_ptr<RollingWindow> matching_window_;  ///< Null: only window_ is matched against.
  MatchingField field_;                             ///< Of window_, updated when a match uses it.
  MatchingField matching_field_;  ///< Of matching_window_, updated when a match uses it.
  keymap::KeyMapBuilder keymaps_;
  OdometryNoiseEstimate odometry_noise_;
  MountingEstimate mounting_;
  MotionCheck motion_check_;
  MatchScoreMonitor score_monitor_;  ///< Scores of the accepted matches.
  LaserNoiseMonitor laser_noise_;    ///< Whether the wall normals are used.
  FrontEndStats stats_;
  Pose2 last_estimate_;     ///< Estimated pose of the previous frame.
  Pose2 last_insert_pose_;  ///< Pose of the last inserted scan.
  Time last_insert_time_;
};

}  // namespace gridslam::scan_matching
