// Internal state of the Mapper (mapper.hpp), shared by its implementation files: mapper.cpp
// (frames, key maps, sequential edges, the online API), mapper_closures.cpp (the prior-based
// and the appearance search for loop closures, handing their alignments to the arbiter),
// mapper_finish.cpp (final optimization, corrected poses, fusion). The decisions live in the
// parts: KeyMapGraph, FeatureAligner, CandidateSelector, loop_closure::ClosureArbiter,
// ComponentJoiner. Not part of the API.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "gridslam/description/keymap_describer.hpp"
#include "gridslam/loop_closure/appearance_index.hpp"
#include "gridslam/loop_closure/closure_arbiter.hpp"
#include "gridslam/pipeline/candidate_selector.hpp"
#include "gridslam/pipeline/component_joiner.hpp"
#include "gridslam/pipeline/key_map_aligner.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/pipeline/snapshot_fusion.hpp"
#include "gridslam/scan_matching/front_end.hpp"

namespace gridslam::pipeline {

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
  /// The robot's key maps for the appearance search (mapper_closures.cpp): one index per robot,
  /// so a query's nearest neighbours are not its own robot's near-duplicates.
  std::unique_ptr<loop_closure::AppearanceIndex> appearance;
  double appearance_travel = -1e300;  ///< Path length at the last key map in `appearance`.
  std::vector<ScanRecord> scans;
  std::size_t unassigned = 0;  ///< First scan not yet given to a key map.
  std::vector<FusionScan> fusion_scans;
  std::size_t unfused = 0;  ///< First fusion scan not yet given to the snapshot fusion.
  double travel = 0.0;
  std::optional<Pose2> last_pose;  ///< Front-end pose of the latest frame.
  /// Odometry pose of the latest frame (its front-end pose when the recording has none).
  Pose2 last_odometry;
  Time last_time;
};

/// What the prior-based search did for a key map.
struct PriorSearch {
  std::vector<int> tried;  ///< The candidates aligned (left out of the appearance search).
  bool changed = false;    ///< Accepted closures that disagree with the estimate: optimize online.
  bool large_correction = false;  ///< An accepted closure corrects beyond the gate floor.
};

struct Mapper::Impl {
  Impl(const MapperOptions& options, int num_robots);

  // mapper.cpp
  void AddFrame(int robot, const Frame& frame);
  void ProcessKeyMap(int robot, keymap::KeyMap key_map, Time time);
  void Iterate(int iterations);
  /// Full optimization of the current graph (options.optimizer), then SGD restarts from it.
  void OptimizeNow();
  void SyncStats();
  /// Maps the robot's front-end frame into its map frame (the newest key map's correction).
  [[nodiscard]] Pose2 MapToFrontEnd(int robot) const;
  MapSnapshot Snapshot();

  // mapper_closures.cpp
  PriorSearch SearchPriorCandidates(int k);
  /// True when an accepted closure calls for online optimization.
  bool SearchAppearance(int k, const std::vector<int>& prior_tried);
  bool OfferWithinMap(const loop_closure::Match& match, double uncertainty_distance);

  // mapper_finish.cpp
  MapperResult Finish();
  void FinalOptimization();
  std::vector<TrajectoryPose> CorrectedTrajectory(int robot, bool interpolate) const;
  [[nodiscard]] std::vector<int> ComponentNumbers() const;

  MapperOptions options;
  description::KeyMapDescriber describer;
  std::vector<RobotState> robots;
  KeyMapGraph graph;
  FeatureAligner aligner;
  CandidateSelector selector;
  loop_closure::ClosureArbiter arbiter;
  ComponentJoiner joiner;
  SnapshotFusion snapshots;
  std::vector<JoinRecord> joins;
  MapperStats stats;
  Time now;
};

/// Seconds since `start` (steady clock).
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace gridslam::pipeline
