// The key-map graph (docs/design.md §1.6, §1.7): the pose graph of the mapper, its vertices (key
// maps with their descriptions), its edges (sequential and loop), the closure records the loop
// edges come from, and the map components (robots whose graphs are joined share one frame).
// Contract: this class is the ONLY writer of vertices, edges and estimates. The online optimizer
// (SGD) always holds exactly the active edges and one anchor per component: an edge is added to
// it when it is added here, and the optimizer is rebuilt whenever components merge or edges are
// removed. Estimates change only through AddKeyMap (chained from the robot's previous key map),
// Iterate, Optimize, MergeComponents and OptimizeAndPrune. Events for the online API are queued
// as they happen (DrainEvents).
#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/check.hpp"
#include "gridslam/description/key_map_cells.hpp"
#include "gridslam/keymap/key_map.hpp"
#include "gridslam/loop_closure/closure_arbiter.hpp"
#include "gridslam/loop_closure/uncertainty_graph.hpp"
#include "gridslam/matching/feature_set.hpp"
#include "gridslam/pipeline/mapper_records.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"

namespace gridslam::pipeline {

/// A key map as a graph vertex (everything but its estimate, which the graph holds).
struct KeyMapNode {
  int id = 0;  ///< Set by AddKeyMap.
  int robot = 0;
  int previous = -1;    ///< The robot's previous key map (vertex id), -1 for its first; set.
  double travel = 0.0;  ///< The robot's path length at the key map [m].
  Time time;
  Pose2 T_odom_key;               ///< In the robot's front-end frame.
  keymap::KeyMap key_map;         ///< Kept only for the nearest-key-map fusion.
  matching::FeatureSet features;  ///< The description's features.
  /// The description's obstacle and observed cells: the distance field and the obstacle points
  /// follow from them (description::ComputeGeometry; FeatureAligner keeps the recent ones).
  description::KeyMapCells cells;
  /// Returns of the key map's own scans in its frame, for refinement (RefinementOptions::points).
  std::vector<Eigen::Vector2d> scan_points;
  bool alignable = false;  ///< Enough features to be aligned.
};

struct EdgeRecord {
  int from = 0;
  int to = 0;
  Pose2 T_from_to;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  bool loop = false;
  bool active = true;
  int closure = -1;  ///< Index into closures() for loop edges.
};

/// Diagonal information of standard deviations sigma_xy [m] (x and y) and sigma_theta [rad].
inline Eigen::Matrix3d Information(double sigma_xy, double sigma_theta) {
  return Eigen::Vector3d(1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_xy * sigma_xy),
                         1.0 / (sigma_theta * sigma_theta))
      .asDiagonal();
}

/// The information of a loop edge: Information(sigma_xy, sigma_theta), and along a ridge's free
/// axis only what the search window tells (1 / free_sigma^2), so the edge stays positive definite
/// but all but free along the axis; along a weak axis (a corridor placed by the search's peak)
/// what the search's step tells (1 / weak_sigma^2, never more than sigma_xy's). The edge's
/// translation error is in the frame of k as measured (g2o's convention,
/// pose_graph/edge_error.hpp), where an axis given in i's frame is R(T_i_k)^T axis.
inline Eigen::Matrix3d LoopInformation(const loop_closure::Match& match, double sigma_xy,
                                       double sigma_theta) {
  Eigen::Matrix3d information = Information(sigma_xy, sigma_theta);
  const auto lower_along = [&](const Eigen::Vector2d& axis_in_i, double sigma) {
    GRIDSLAM_CHECK(sigma > 0.0) << sigma;
    const Eigen::Vector2d axis = match.T_i_k.Rotation().transpose() * axis_in_i;
    const Eigen::Matrix2d along = axis * axis.transpose();
    information.topLeftCorner<2, 2>() =
        (Eigen::Matrix2d::Identity() - along) / (sigma_xy * sigma_xy) + along / (sigma * sigma);
  };
  if (match.free_axis.has_value()) {
    lower_along(*match.free_axis, match.free_sigma);
  } else if (match.weak_axis.has_value()) {
    lower_along(*match.weak_axis, std::max(match.weak_sigma, sigma_xy));  // never more than full
  }
  return information;
}

/// A loop edge's weight in the uncertainty distance: `loop_uncertainty` [m], or infinite for a
/// ridge, whose position along its free axis is as uncertain as before.
inline double LoopUncertaintyWeight(const loop_closure::Match& match, double loop_uncertainty) {
  return match.free_axis.has_value() ? std::numeric_limits<double>::infinity() : loop_uncertainty;
}

class KeyMapGraph : public loop_closure::GraphView {
 public:
  KeyMapGraph(int num_robots, const pose_graph::SgdOptions& sgd);

  /// Adds a key map of `node.robot` as the next vertex; sets its id and previous; its estimate
  /// is the previous key map's composed with the front-end motion (a robot's first key map: its
  /// front-end pose, anchored). Returns the id.
  int AddKeyMap(KeyMapNode node);
  /// Adds an edge between existing vertices, weighing `uncertainty_weight` [m] in the
  /// uncertainty distance.
  void AddEdge(const EdgeRecord& edge, double uncertainty_weight);
  /// Adds a loop edge from `match` with its closure record (outcome kAccepted or kJoined);
  /// returns the record's index.
  int AddLoopEdge(const loop_closure::Match& match, ClosureOutcome outcome, bool appearance,
                  const Eigen::Matrix3d& information, double uncertainty_weight);
  /// Records a closure that is not an edge (kGated, kPending); returns its index.
  int RecordClosure(const loop_closure::Match& match, ClosureOutcome outcome, bool appearance);
  /// Adds the loop edge of a gated closure accepted later: every record of (match.i, match.k)
  /// still gated becomes accepted, and the edge points at the last of them.
  void AcceptGated(const loop_closure::Match& match, const Eigen::Matrix3d& information,
                   double uncertainty_weight);

  /// `iterations` of online SGD; the estimates follow.
  void Iterate(int iterations);
  /// Full optimization of the current graph, then SGD restarts from it.
  void Optimize(const pose_graph::OptimizerOptions& options);
  /// Moves every key map of robot_b's component by T_a_b (into robot_a's frame) and merges the
  /// two components.
  void MergeComponents(int robot_a, int robot_b, const Pose2& T_a_b, Time time);

  struct FinalResult {
    double chi2 = 0.0;  ///< chi2 of the graph at its optimum (= of final_graph()).
    int pruned = 0;     ///< Loop edges removed.
  };
  /// Optimizes (`options`, method `method`, "none" = not at all), removes the loop edge of the
  /// highest chi2 above `prune_chi2`, and again, at most `prune_rounds` times; the graph is
  /// optimized once more after the last removal, so the result is the optimum of exactly the
  /// remaining edges.
  FinalResult OptimizeAndPrune(const pose_graph::OptimizerOptions& options,
                               const std::string& method, int prune_rounds, double prune_chi2);

  // GraphView.
  [[nodiscard]] Pose2 Estimate(int id) const override;
  [[nodiscard]] double Travel(int id) const override { return node(id).travel; }
  [[nodiscard]] int Robot(int id) const override { return node(id).robot; }
  [[nodiscard]] int Component(int id) const override { return RobotComponent(node(id).robot); }

  /// Representative robot of `robot`'s map component.
  [[nodiscard]] int RobotComponent(int robot) const;
  [[nodiscard]] int num_robots() const { return static_cast<int>(last_node_.size()); }
  /// The robot's newest key map, -1 if none; its number of key maps.
  [[nodiscard]] int LastKeyMap(int robot) const {
    return last_node_[static_cast<std::size_t>(robot)];
  }
  [[nodiscard]] int NumKeyMaps(int robot) const {
    return num_nodes_[static_cast<std::size_t>(robot)];
  }
  [[nodiscard]] const KeyMapNode& node(int id) const {
    return nodes_[static_cast<std::size_t>(id)];
  }
  /// Every vertex by id (a deque: references stay valid as vertices are added).
  [[nodiscard]] const std::deque<KeyMapNode>& nodes() const { return nodes_; }
  [[nodiscard]] int size() const { return static_cast<int>(nodes_.size()); }
  [[nodiscard]] const std::vector<EdgeRecord>& edges() const { return edges_; }
  [[nodiscard]] const std::vector<ClosureRecord>& closures() const { return closures_; }
  /// Uncertainty distance from `id` to every vertex [m] (loop_closure/uncertainty_graph.hpp).
  [[nodiscard]] std::vector<double> DistancesFrom(int id) const {
    return uncertainty_.DistancesFrom(id);
  }
  /// ... only as far as `targets` need (UncertaintyGraph::DistancesFrom with targets: the others
  /// may be NaN).
  [[nodiscard]] std::vector<double> DistancesFrom(int id, const std::vector<int>& targets) const {
    return uncertainty_.DistancesFrom(id, targets);
  }
  /// The optimizer's graph: current estimates, active edges, one anchor per component.
  [[nodiscard]] const pose_graph::PoseGraph& ActiveGraph() const { return sgd_->graph(); }
  [[nodiscard]] long loop_edges_added() const { return loop_edges_added_; }
  [[nodiscard]] long NumClosures(ClosureOutcome outcome) const;

  /// Events since the last call (key maps added, closures accepted or removed, joins).
  std::vector<MapperEvent> DrainEvents();
  /// The time stamped on events from now on.
  void SetTime(Time now) { now_ = now; }

 private:
  void RebuildOptimizer();
  void SyncEstimates(const pose_graph::PoseGraph& graph);
  void SetOutcome(int closure, ClosureOutcome outcome);

  pose_graph::SgdOptions sgd_options_;
  std::deque<KeyMapNode> nodes_;
  std::vector<Pose2> estimates_;  ///< T_map_key by vertex id.
  std::vector<EdgeRecord> edges_;
  std::vector<ClosureRecord> closures_;
  /// Records still gated, by (from, to): AcceptGated looks up its pair, not every record.
  std::unordered_map<std::uint64_t, std::vector<int>> gated_records_;
  [[nodiscard]] static std::uint64_t PairKey(int from, int to) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) |
           static_cast<std::uint32_t>(to);
  }
  std::vector<int> robot_parent_;  ///< Union-find of robots joined into one map.
  std::vector<int> last_node_;
  std::vector<int> num_nodes_;
  loop_closure::UncertaintyGraph uncertainty_;
  std::unique_ptr<pose_graph::SgdOptimizer> sgd_;
  long loop_edges_added_ = 0;
  std::vector<long> outcome_counts_ = std::vector<long>(5, 0);
  std::vector<MapperEvent> events_;
  Time now_;
};

}  // namespace gridslam::pipeline
