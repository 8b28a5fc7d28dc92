// The graph-SLAM mapper (DESIGN.md §1; Gil, Juliá, Reinoso 2015): frames of one or several robots
// go in one at a time; each robot's front end turns them into key maps; every key map is
// described (distance transform + SURF), becomes a vertex of the pose graph with a sequential
// edge to the robot's previous key map, and is matched against earlier key maps for loop
// closures: candidates predicted by the current estimate, and a global appearance search across
// robots that have not met yet. Accepted closures are optimized online with SGD; Finish() polishes
// the graph, prunes inconsistent loop edges, derives every scan's corrected pose and fuses the
// global grid. One code path for online and batch use: batch = AddFrame in log order + Finish.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gridslam/common/time.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"
#include "gridslam/scan/laser_scan.hpp"

namespace gridslam::pipeline {

/// A corrected scan pose.
struct TrajectoryPose {
  Time time;
  Pose2 T_map_base;
};

/// One loop-closure attempt that got as far as a verified alignment.
struct ClosureRecord {
  int from = 0;  ///< Older key map (vertex id).
  int to = 0;    ///< Newer key map.
  Pose2 T_from_to;
  std::string outcome;      ///< accepted, gate, pending, joined, pruned.
  bool appearance = false;  ///< Found by the appearance search (no prior).
};

/// When two robots' graphs were joined.
struct JoinRecord {
  int robot_a = 0;
  int robot_b = 0;
  Time time;         ///< Time of the frame that completed the join.
  int vertex_a = 0;  ///< The first matched key maps.
  int vertex_b = 0;
  int matches = 0;  ///< Consistent matches used.
};

struct MapperStats {
  long frames = 0;
  long key_maps = 0;
  long described = 0;
  long featureless = 0;  ///< Key maps with too few features to align.
  long sequential_aligned = 0;
  long candidates = 0;  ///< Prior-based candidates aligned.
  long appearance_queries = 0;
  long appearance_candidates = 0;
  long verified = 0;       ///< Alignments accepted by matching + verification.
  long prior_refined = 0;  ///< Of which: found by refinement from the prediction (no features).
  long online_full_optimizations = 0;  ///< After closures correcting beyond the gate floor.
  long prior_searches = 0;  ///< Correlative searches around the prediction (prior_search.hpp).
  long accepted = 0;        ///< Loop edges added.
  long rejected_gate = 0;
  long pruned = 0;
  long joins = 0;
  double seconds_front_end = 0.0;
  double seconds_description = 0.0;
  double seconds_alignment = 0.0;
  double seconds_optimization = 0.0;
  double seconds_final = 0.0;
  double seconds_fusion = 0.0;
  double chi2_final = 0.0;
};

struct MapperResult {
  std::vector<std::vector<TrajectoryPose>> trajectories;  ///< Per robot, every scan.
  pose_graph::PoseGraph graph;                            ///< Optimized key-map graph.
  std::vector<int> vertex_robot;                          ///< Robot of each vertex (by vertex id).
  std::vector<int> component_of_robot;  ///< Robots with the same value share one map frame.
  std::vector<ClosureRecord> closures;
  std::vector<JoinRecord> joins;
  /// Fused log-odds grid per map component (index = component value of component_of_robot).
  std::vector<Grid2D<float>> maps;
  MapperStats stats;
};

class Mapper {
 public:
  /// `options` must be valid. `num_robots` >= 1.
  Mapper(const SlamOptions& options, int num_robots);
  ~Mapper();
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  /// Processes the next frame of robot `robot` (frames of each robot in its log order; robots
  /// interleaved by time as a team would deliver them).
  void AddFrame(int robot, const Frame& frame);
  /// Ends the run: final optimization, corrected poses, fusion.
  MapperResult Finish();
  /// Current statistics (also during the run).
  [[nodiscard]] const MapperStats& Stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gridslam::pipeline
