// When is a scan match poor (front_end.hpp)? The score of a match (the share of the scan's points
// that lie on the local map) depends on the scene as much as on the pose: an office explains
// 0.95-1.0 of a scan, a hall with people, glass and returns at 30 m 0.6-0.9. A fixed threshold
// (matcher.good_score, 0.5) is either blind in the office or fires everywhere in the hall. This
// monitor judges a score against the scores of the recent accepted matches instead: a match is
// poor when it falls below their median by more than `sigmas` robust standard deviations (1.4826
// x the median absolute deviation) and by at least `min_drop`. A sudden drop is what a wrong
// prediction looks like (odometry that reports forward motion while the robot reverses; a slip),
// while a scene that is merely hard keeps its usual level and spread. A pose that is to replace
// the prediction must then score as the recent matches usually do (within `usual_sigmas`): a
// pose that is merely less poor (a scan half hidden by a passer-by, fitted elsewhere) is not one.
#pragma once

#include <cstddef>
#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"

namespace gridslam::scan_matching {

struct PoorMatchOptions {
  /// Search widely when a match with odometry is poor, and let a clearly better, unambiguous pose
  /// overrule the odometry.
  bool enabled = true;
  int window = 100;        ///< Recent accepted scores in the statistics [-].
  double sigmas = 6.0;     ///< A drop beyond this many robust standard deviations is poor [-].
  double min_drop = 0.15;  ///< ... and beyond this much below the median [-].
  /// A pose that is to overrule the odometry must score like the recent matches: no lower than
  /// this many robust standard deviations below their median [-].
  double usual_sigmas = 2.0;
  double usual_floor = 0.05;  ///< ... and always within this much of it [-].

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled,
      "Search widely when a match with odometry scores far below the recent matches");
    v("window", window, "Recent accepted match scores in the statistics [-]");
    v("sigmas", sigmas, "A score below the median by this many robust std is poor [-]");
    v("min_drop", min_drop, "... and by at least this much [-]");
    v("usual_sigmas", usual_sigmas,
      "A pose overruling the odometry scores within this many robust std of the median [-]");
    v("usual_floor", usual_floor, "... and always may score this much below the median [-]");
  }
  [[nodiscard]] Status Validate() const {
    return Require(window > 0 && sigmas > 0.0 && min_drop > 0.0 && min_drop < 1.0 &&
                       usual_sigmas >= 0.0 && usual_sigmas <= sigmas && usual_floor >= 0.0 &&
                       usual_floor <= min_drop,
                   "front_end.poor_match: window > 0, sigmas > 0, 0 < min_drop < 1, "
                   "0 <= usual_sigmas <= sigmas, 0 <= usual_floor <= min_drop");
  }
};

/// A pose the wide search found, refined, and the score of its match.
struct ScoredPose {
  Pose2 pose;
  double score = 0.0;
};

/// What became of a poor match's wide search.
enum class RescueVerdict {
  kNone,       ///< No refinement to judge.
  kNotClear,   ///< The best is not clearly better than the poor match, or not a usual score.
  kAmbiguous,  ///< Another pose, distinct from the best, explains the scan about as well.
  kRescued,    ///< The best pose overrules the prediction.
};

const char* ToString(RescueVerdict verdict);

struct RescueChoice {
  RescueVerdict verdict = RescueVerdict::kNone;
  std::size_t best = 0;    ///< Index of the best-scoring candidate (verdict != kNone).
  bool has_rival = false;  ///< A candidate at a distinct pose, as near the prediction, exists.
  std::size_t rival = 0;   ///< The best of those.
};

/// How the rescue is judged: `good_score` (matcher.good_score), the score `margin` a pose must
/// gain over the poor match and keep over any distinct rival, and the separation beyond which
/// two poses are distinct [m], [rad].
struct RescueRule {
  double good_score = 0.5;
  double margin = 0.05;
  double separation_xy = 0.3;
  double separation_theta = 0.07;
  /// The scale of "near the prediction": the wide search's half-widths [m], [rad].
  double window_xy = 1.0;
  double window_theta = 1.5707963267948966;
};

class MatchScoreMonitor {
 public:
  explicit MatchScoreMonitor(const PoorMatchOptions& options);

  /// Records the score of an accepted match.
  void Add(double score);
  /// `score` is poor against the recent ones; never before the window has filled once.
  [[nodiscard]] bool Poor(double score) const;
  /// `score` is as good as the recent ones usually are (within usual_sigmas robust std or
  /// usual_floor of their median);
  /// false before the window has filled once.
  [[nodiscard]] bool Usual(double score) const { return score >= usual_; }
  /// Judges the wide search's `candidates` around `prediction` after a poor match of score
  /// `poor_score` (negative: the match failed): the best one overrules the prediction if it
  /// scores at least good_score, more than poor_score + margin and as the recent matches usually
  /// do (Usual), and no candidate at a distinct pose that is at least as near the prediction
  /// comes within `margin` of it. Between look-alikes the prediction decides: a rival farther
  /// from it is no reason to doubt the best pose.
  [[nodiscard]] RescueChoice Choose(const std::vector<ScoredPose>& candidates,
                                    const Pose2& prediction, double poor_score,
                                    const RescueRule& rule) const;
  /// Scores below this are poor (-infinity before the window has filled once).
  [[nodiscard]] double Threshold() const { return threshold_; }

 private:
  PoorMatchOptions options_;
  std::vector<double> scores_;  ///< Ring buffer.
  std::size_t next_ = 0;
  double threshold_;
  double usual_;
};

}  // namespace gridslam::scan_matching
