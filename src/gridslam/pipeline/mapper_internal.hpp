// Internal state of the Mapper (mapper.hpp), shared by its implementation files:
// mapper.cpp (frames, key maps, sequential edges), mapper_closures.cpp (loop closures, the
// appearance search, joining robots), mapper_finish.cpp (final optimization, corrected poses,
// fusion). Not part of the API.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "gridslam/description/keymap_describer.hpp"
#include "gridslam/keymap/key_map.hpp"
#include "gridslam/loop_closure/appearance_index.hpp"
#include "gridslam/loop_closure/uncertainty_graph.hpp"
#include "gridslam/matching/grid_verification.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"
#include "gridslam/scan_matching/front_end.hpp"

namespace gridslam::pipeline {

/// A key map as a graph vertex.
struct Node {
  int id = 0;
  int robot = 0;
  int previous = -1;    ///< The robot's previous key map (vertex id), -1 for its first.
  double travel = 0.0;  ///< The robot's path length at the key map [m].
  Time time;
  Pose2 T_odom_key;        ///< In the robot's front-end frame.
  Pose2 estimate;          ///< T_map_key, current estimate.
  keymap::KeyMap key_map;  ///< Kept only for the nearest-key-map fusion.
  description::KeyMapDescription description;
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
  int closure = -1;  ///< Index into closures_ for loop edges.
};

struct ScanRecord {
  Time time;
  Pose2 T_odom_base;  ///< Front-end pose.
  double travel = 0.0;
  int node = -1;  ///< The key map holding the scan.
};

struct FusionScan {
  std::size_t scan_index = 0;  ///< Into RobotState::scans.
  Pose2 T_base_laser;
  LaserScan scan;
};

struct RobotState {
  std::unique_ptr<scan_matching::FrontEnd> front_end;
  /// The robot's key maps for the other robots' appearance search (mapper_join.cpp): one index
  /// per robot, so a query's nearest neighbours are not its own robot's near-duplicates.
  std::unique_ptr<loop_closure::AppearanceIndex> appearance;
  double appearance_travel = -1e300;  ///< Path length at the last key map in `appearance`.
  std::vector<ScanRecord> scans;
  std::size_t unassigned = 0;  ///< First scan not yet given to a key map.
  std::vector<FusionScan> fusion_scans;
  int last_node = -1;
  int num_nodes = 0;
  double travel = 0.0;
  std::optional<Pose2> last_pose;
  Time last_time;
};

/// A verified match between two robots' graphs that are not joined yet.
struct PendingJoin {
  int i = 0;  ///< Vertex of the older component.
  int k = 0;  ///< Vertex of the newer key map's component.
  Pose2 T_i_k;
};

struct Mapper::Impl {
  Impl(const SlamOptions& options, int num_robots);

  // mapper.cpp
  void AddFrame(int robot, const Frame& frame);
  void ProcessKeyMap(int robot, keymap::KeyMap key_map, Time time);
  void AddEdge(EdgeRecord edge, double uncertainty);
  void Iterate(int iterations);
  void SyncEstimates();
  void RebuildOptimizer();
  int FindComponent(int robot);
  [[nodiscard]] Eigen::Matrix3d Information(double sigma_xy, double sigma_theta) const;
  /// The points of key map b refined against another map's distance field.
  [[nodiscard]] std::span<const Eigen::Vector2d> RefinementPoints(const Node& b) const;

  // mapper_closures.cpp
  /// Feature alignment of k to i (refined, verified); with a `prior` (T_i_k predicted), a failed
  /// feature alignment falls back to RefineFromPrior.
  /// `uncertainty_distance`: the uncertainty distance between the key maps [m] (sizes the search).
  std::optional<Pose2> TryAlign(int i, int k, const Pose2* prior,
                                double uncertainty_distance = 0.0);
  /// Grid-to-grid refinement from a predicted transform (seeded by a correlative search when the
  /// uncertainty distance allows a large prediction error), accepted only if well constrained
  /// and verified.
  std::optional<Pose2> RefineFromPrior(int i, int k, const Pose2& T_i_k,
                                       const matching::VerificationInput& verification,
                                       double uncertainty_distance);
  /// True when an accepted closure calls for online optimization.
  bool SearchPriorCandidates(int k);

  // mapper_join.cpp
  bool SearchAppearance(int k);
  bool AcceptAcrossRobots(int i, int k, const Pose2& T_i_k, std::vector<double>& distance);
  void Join(int k, const std::vector<PendingJoin>& matches);
  /// After a join: aligns each key map of the moved robots (`moved`, by robot) with the nearest
  /// key maps of the others; keeps the matches that agree with min_join_matches others.
  void CatchUp(const std::vector<bool>& moved, std::vector<PendingJoin> trusted);
  /// Full optimization of the current graph (options.optimizer), then SGD restarts from it.
  void OptimizeNow();

  // mapper_finish.cpp
  MapperResult Finish();
  void FinalOptimization();
  std::vector<TrajectoryPose> CorrectedTrajectory(int robot) const;

  SlamOptions options;
  description::KeyMapDescriber describer;
  std::vector<RobotState> robots;
  std::vector<int> robot_parent;  ///< Union-find of robots joined into one map.
  std::vector<Node> nodes;
  std::vector<EdgeRecord> edges;
  std::vector<ClosureRecord> closures;
  std::vector<JoinRecord> joins;
  std::vector<PendingJoin> pending;
  /// Verified appearance matches between robots of one map that disagree with the estimate,
  /// awaiting independent matches that agree with them (mapper_join.cpp).
  std::vector<PendingJoin> across;
  std::vector<PendingJoin> gated;  ///< Verified closures outside the gate, awaiting support.
  std::vector<int> prior_tried;    ///< Key maps the last prior-based search aligned.
  bool searched_ = false;          ///< The last prior refinement was seeded by a search.
  bool large_correction_ = false;  ///< The last search accepted a closure beyond the gate floor.
  loop_closure::UncertaintyGraph uncertainty;
  std::unique_ptr<pose_graph::SgdOptimizer> sgd;
  MapperStats stats;
  Time now;
};

/// Seconds since `start` (steady clock).
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace gridslam::pipeline
