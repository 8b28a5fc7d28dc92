// Internal state of the Mapper (mapper.hpp), shared by its implementation files: mapper.cpp
// (frames, key maps, sequential edges, the online API), mapper_closures.cpp (the prior-based
// and the appearance search for loop closures, handing their alignments to the arbiter),
// mapper_finish.cpp (final optimization, corrected poses, fusion), key_map_worker.cpp (the
// thread that integrates key maps). The decisions live in the parts: KeyMapGraph,
// FeatureAligner, CandidateSelector, loop_closure::ClosureArbiter, ComponentJoiner. Not part of
// the API.
//
// Threads (compute.threads >= 2): the caller's thread runs the front ends and keeps the scans
// (the "front" state below); a worker thread integrates the key maps in the order they were made
// (the "back" state: the graph and everything that reads or writes it). A key map's integration
// reads nothing the front changes afterwards (its robot's path length and its time travel with
// it), so integrating it later gives what integrating it at once gives: the results do not
// depend on the threads. Every call that reads the back state (the online API, Finish) first
// waits until the worker has integrated every key map made so far (Sync).
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
#include "gridslam/pipeline/join_verifier.hpp"
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
  /// Where the scans put the laser (FrontEnd::Mounting), kept when the front end is released.
  scan_matching::MountingResult mounting;
};

/// A key map's description and the returns of its scans (pure functions of the key map: either
/// thread may compute them).
struct DescribedKeyMap {
  description::KeyMapDescription description;
  std::vector<Eigen::Vector2d> scan_points;  ///< For refinement (RefinementOptions::points).
  double seconds = 0.0;
};

/// A key map on its way from a front end to the graph.
struct KeyMapJob {
  int robot = 0;
  int id = 0;  ///< Its vertex id: key maps are integrated in the order they are made.
  keymap::KeyMap key_map;
  Time time;            ///< The key map's time (KeyMapNode::time).
  Time event_time;      ///< The latest frame's time when it was made (events, joins).
  double travel = 0.0;  ///< The robot's path length when it was made.
  std::optional<DescribedKeyMap> described;  ///< Set by whichever thread describes it.
};

class KeyMapWorker;

/// What the prior-based search did for a key map.
struct PriorSearch {
  std::vector<int> tried;  ///< The candidates aligned (left out of the appearance search).
  bool changed = false;    ///< Accepted closures that disagree with the estimate: optimize online.
  bool large_correction = false;  ///< An accepted closure corrects beyond the gate floor.
};

struct Mapper::Impl {
  Impl(const MapperOptions& options, int num_robots);

  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  // mapper.cpp
  void AddFrame(int robot, const Frame& frame);
  /// Front: hands a new key map of `robot` to the graph (at once, or to the worker).
  void SubmitKeyMap(int robot, keymap::KeyMap key_map, Time time);
  [[nodiscard]] DescribedKeyMap Describe(const keymap::KeyMap& key_map) const;
  /// Back: the key map becomes a vertex, with its sequential edge and its loop closures.
  void IntegrateKeyMap(KeyMapJob& job);
  /// Waits until every key map made so far is integrated (no-op with one thread).
  void Sync();
  /// stats with the front's counters (after Sync).
  [[nodiscard]] MapperStats MergedStats() const;
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
  /// Verifies loop_hypothesis (JoinVerifier); adds its loop edges and optimizes when confirmed.
  bool VerifyLoopHypothesis();
  /// The free-space check of a join (join_free_space.hpp); counts and logs a refusal.
  bool FreeSpaceAllowsJoin(const std::vector<loop_closure::Match>& group);
  /// Once key map k (of the hypothesis's robot) is in the graph: verifies the pending
  /// hypothesis again while k lies within loop_verification_travel after it, drops it beyond.
  void RetryLoopHypothesis(int k);

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
  JoinVerifier join_verifier;
  int loop_verified_k = -1;  ///< The last key map whose waiting appearance match was verified.
  /// The latest waiting appearance match inside one map that its key maps did not confirm yet.
  std::optional<loop_closure::Match> loop_hypothesis;
  SnapshotFusion snapshots;
  std::vector<JoinRecord> joins;
  MapperStats stats;  ///< Back: everything but the front's counters.
  Time now;           ///< Back: the event time of the key map being integrated.
  /// FLANN's random state of the appearance indices, shared in the order their blocks are
  /// built, whichever thread builds them.
  std::shared_ptr<cv::RNG> appearance_rng;

  // Front (the caller's thread).
  MapperStats front_stats;  ///< frames, odometry counters, seconds_front_end.
  Time front_now;           ///< Time of the latest frame.
  int key_maps_made = 0;
  MapperStats reported;                  ///< What Stats() returns.
  std::unique_ptr<KeyMapWorker> worker;  ///< Null with one thread.
};

/// Seconds since `start` (steady clock).
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace gridslam::pipeline
