// Correlative search for a loop closure around a predicted transform (docs/design.md §1.6), for the
// key maps whose feature alignment fails (sparse maps: open halls, rows of poles) while the
// graph's prediction is off by more than the distance-field refinement's basin (about the
// refinement's max_distance). After a long loop the prediction's error grows with the path
// length between the key maps; the search window does too: every pose on a regular grid of
// translations (linear_step) and rotations (angular_step) within the window is scored by the
// mean truncated distance of b's obstacle points in a's distance field, score = mean over the
// points of max(0, 1 - d / truncation) (points on a's unknown cells or outside it score 0), as
// in correlative scan matching (Olson, ICRA 2009), on a's exact distance transform. The best pose
// seeds RefineOnDistanceField. Because the window is large, the search also reports how
// distinct the best pose is: the best score among the poses farther than `distinct_distance`
// from it, so that a corridor or a row of identical bays (many equally good poses) can be refused.
// The windows grow with the uncertainty distance up to metres and tenths of a radian: the lattice
// is searched by branch and bound (Hess et al., ICRA 2016) on max pools of the score, which finds
// the exhaustive search's best score while scoring a small part of the lattice.
#pragma once

#include <span>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::loop_closure {

struct PriorSearchOptions {
  bool enabled = true;
  /// Half-width of the translation window: this fraction of the uncertainty distance between
  /// the key maps (graph path length, a drift rate) ... [m/m]
  double window_per_m = 0.02;
  double max_window_xy = 10.0;  ///< ... capped here [m].
  /// When that window finds nothing, a second search covers the drift the loop-closure arbiter
  /// allows an appearance match (loop_closure.max_drift, 5 % of the uncertainty distance; also
  /// capped at max_window_xy). A drift that outgrew the first window lands here; so may a
  /// look-alike, so its closures are accepted only in a group holding two independent matches
  /// (closure_arbiter.hpp). 0 = no second search [m/m].
  double wide_window_per_m = 0.05;
  double min_window_xy = 0.5;  ///< Smaller windows: the refinement alone is used [m].
  /// Half-width of the rotation window: window_theta_per_m times the uncertainty distance (a
  /// heading drift rate) [rad/m], at least window_theta [rad], at most max_window_theta [rad].
  double window_theta_per_m = 0.0005;
  double window_theta = 0.1;
  double max_window_theta = 0.35;
  double linear_step = 0.2;     ///< Translation step of the grid (rounded to cells) [m].
  double angular_step = 0.035;  ///< Rotation step [rad].
  double truncation = 0.3;      ///< Distances beyond this score 0 [m].
  int max_points = 400;         ///< b's points used at most (regular subsample) [-].
  double min_score = 0.3;       ///< Best scores below this: no match [-].
  /// The best score among poses farther than distinct_distance from the best must stay below
  /// max_ambiguity times the best [m], [-].
  double distinct_distance = 0.5;
  double max_ambiguity = 0.85;
  /// When every rival lies on the line through the best pose and the best rival (within
  /// distinct_distance of it: a corridor, a straight road), accept the search as a ridge: its
  /// heading and its offset across the line are measured, its position along the line is not.
  bool ridge_closures = true;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled,
      "Search a window around the prediction when feature alignment fails and the prediction "
      "may be off by more than the refinement converges from");
    v("window_per_m", window_per_m,
      "Translation half-window per metre of uncertainty distance (drift rate) [m/m]");
    v("max_window_xy", max_window_xy, "... capped here [m]");
    v("wide_window_per_m", wide_window_per_m,
      "Second search when the first finds nothing: half-window per metre of uncertainty "
      "distance; its closures need independent support (0 = none) [m/m]");
    v("min_window_xy", min_window_xy, "Smaller windows: refine the prediction only [m]");
    v("window_theta_per_m", window_theta_per_m,
      "Rotation half-window per metre of uncertainty distance (heading drift rate) [rad/m]");
    v("window_theta", window_theta, "Smallest rotation half-window [rad]");
    v("max_window_theta", max_window_theta, "Largest rotation half-window [rad]");
    v("linear_step", linear_step, "Translation step of the search grid [m]");
    v("angular_step", angular_step, "Rotation step of the search grid [rad]");
    v("truncation", truncation, "Points farther than this from an obstacle score 0 [m]");
    v("max_points", max_points, "Points of the newer key map used at most [-]");
    v("min_score", min_score, "Minimum best score (mean truncated closeness) [-]");
    v("distinct_distance", distinct_distance,
      "Poses farther than this from the best are its rivals [m]");
    v("max_ambiguity", max_ambiguity,
      "Refused when the best rival scores more than this fraction of the best [-]");
    v("ridge_closures", ridge_closures,
      "Accept a search whose rivals all lie on one line through the best pose, with the "
      "position along that line left unmeasured");
  }
  [[nodiscard]] Status Validate() const;
  /// The translation and rotation half-windows for an uncertainty distance [m] -> [m], [rad].
  [[nodiscard]] double WindowXy(double uncertainty_distance) const;
  /// The second search's translation half-window [m] (0 when there is none).
  [[nodiscard]] double WideWindowXy(double uncertainty_distance) const;
  [[nodiscard]] double WindowTheta(double uncertainty_distance) const;
};

struct PriorSearchResult {
  /// Best score >= min_score, and distinct enough or a ridge.
  bool ok = false;
  Pose2 T_a_b;         ///< Best pose of the grid.
  double score = 0.0;  ///< Its score [-]; 0 when no pose reaches min_score.
  /// Best score farther than distinct_distance from it [-]. Branch and bound finds it only when
  /// it exceeds max_ambiguity times the best (the search refuses) and reports 0 otherwise (it
  /// needs no more); the exhaustive search, which SearchAroundPrior runs for small windows,
  /// reports it always.
  double rival = 0.0;
  /// The rivals all lie within distinct_distance of the line through the best pose along
  /// ridge_axis (unit, a's frame): the translation along it is not measured (ridge_closures).
  bool ridge = false;
  Eigen::Vector2d ridge_axis = Eigen::Vector2d::Zero();
  /// Best score of the poses farther than distinct_distance from that line [-], computed only
  /// when the rival is ambiguous (branch and bound: only when it exceeds max_ambiguity times the
  /// best, 0 otherwise).
  double off_ridge = 0.0;
  long poses = 0;   ///< Poses in the window's lattice.
  long scored = 0;  ///< Bounds and poses evaluated.
};

/// Searches T_a_b (p_a = T_a_b * p_b) within +-window_xy [m] (translation of b's origin in a's
/// frame) and +-window_theta [rad] (rotation about b's origin) of `prior`. `distance_a`: metres
/// to a's nearest obstacle, negative on unknown cells. Deterministic; thread-safe.
PriorSearchResult SearchAroundPrior(std::span<const Eigen::Vector2d> points_b,
                                    const Grid2D<float>& distance_a, const Pose2& prior,
                                    double window_xy, double window_theta,
                                    const PriorSearchOptions& options);

/// The same search scoring every pose of the lattice, with the exact rival (the reference of
/// SearchAroundPrior's tests; its cost grows with the window's area times its rotations).
PriorSearchResult SearchAroundPriorExhaustive(std::span<const Eigen::Vector2d> points_b,
                                              const Grid2D<float>& distance_a, const Pose2& prior,
                                              double window_xy, double window_theta,
                                              const PriorSearchOptions& options);

namespace internal {

/// The cells a bound of SearchAroundPrior's branch and bound reads in a `width` x `height` grid
/// (row-major, followed by one more cell, index width * height, holding 0): for point k, the
/// block whose first cell is (ci[k] + di, cj[k] + dj) and which reaches `reach` cells along x and
/// y reads its first cell clipped to the grid, or the zero cell when it misses the grid. Written
/// to `cells` (ci.size() of them) in one branch-free pass that the compiler vectorizes, so that
/// summing the points is a plain gather in their order. width * height must fit an int.
void BlockCells(std::span<const int> ci, std::span<const int> cj, int di, int dj, int reach,
                int width, int height, std::span<int> cells);

/// out[i] = the larger of out[i] and in[i] (as std::max(out[i], in[i])), for i < out.size();
/// `in` holds at least as many values. The passes that build the prior search's max pools.
void MaxInto(std::span<float> out, std::span<const float> in);

/// out[i] = the larger of a[i] and b[i] (as std::max(a[i], b[i])), for i < out.size(); `out`
/// does not overlap `a` or `b` unless it is one of them.
void MaxOf(std::span<float> out, std::span<const float> a, std::span<const float> b);

/// out[i] = the larger of in[i] and in[i + shift] where i + shift < out.size(), in[i] beyond
/// (shift >= 0; `in` holds out.size() values, `out` does not overlap it).
void ShiftedMax(std::span<float> out, std::span<const float> in, int shift);

/// score[c] = max(0, 1 - distance[c] / truncation) as the prior search scores a point on cell c
/// (in floats: 1 - d * inv_truncation), 0 on unknown cells (negative distances), for every
/// cell of `distance`; `score` holds at least as many.
void TruncatedScores(std::span<const float> distance, float inv_truncation, std::span<float> score);

/// The smallest u >= 0 with start + u * step >= bound (step > 0; at most INT_MAX): the first of
/// a row of lattice steps from `start` that reaches `bound`.
int FirstStepAtLeast(int start, int step, int bound);

}  // namespace internal

}  // namespace gridslam::loop_closure
