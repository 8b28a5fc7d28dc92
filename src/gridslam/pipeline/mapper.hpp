// The graph-SLAM mapper (docs/design.md §1; Gil, Juliá, Reinoso 2015): frames of one or several
// robots go in one at a time; each robot's front end turns them into key maps; every key map is
// described (distance transform + SURF), becomes a vertex of the pose graph with a sequential
// edge to the robot's previous key map, and is matched against earlier key maps for loop
// closures: candidates predicted by the current estimate, and a global appearance search across
// robots that have not met yet. Accepted closures are optimized online with SGD; Finish() polishes
// the graph, prunes inconsistent loop edges, derives every scan's corrected pose and fuses the
// global grid. One code path for online and batch use: batch = AddFrame in log order + Finish.
//
// The mapper composes its parts (each with its own contract and tests): the key-map graph
// (key_map_graph.hpp, the only writer of vertices, edges and estimates), the aligner
// (key_map_aligner.hpp), the candidate selector (candidate_selector.hpp), the closure arbiter
// (loop_closure/closure_arbiter.hpp: gates, consistent groups, waiting queues) and the component
// joiner (component_joiner.hpp).
//
// Online API (docs/online_api.md): between frames, CurrentPose / MapToOdom give each robot's
// pose in its map frame, Snapshot() the trajectories and the fused maps so far (incremental:
// only key maps that moved are fused again), DrainEvents() what happened since the last call.
// Not thread-safe: call everything from one thread (or guard the Mapper with a mutex).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gridslam/common/time.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/tiled_grid.hpp"
#include "gridslam/pipeline/mapper_options.hpp"
#include "gridslam/pipeline/mapper_records.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"
#include "gridslam/scan/laser_scan.hpp"
#include "gridslam/scan_matching/mounting_estimate.hpp"

namespace gridslam::pipeline {

/// A corrected scan pose.
struct TrajectoryPose {
  Time time;
  Pose2 T_map_base;
};

struct MapperStats {
  long frames = 0;
  long key_maps = 0;
  long described = 0;
  long featureless = 0;  ///< Key maps with too few features to align.
  long sequential_aligned = 0;
  long candidates = 0;  ///< Prior-based candidates aligned.
  /// Key maps aligned to verify a lone match (JoinVerifier) or to extend a join
  /// (ComponentJoiner): alignments neither search proposed.
  long verification_alignments = 0;
  long appearance_queries = 0;
  long appearance_candidates = 0;
  long verified = 0;       ///< Alignments accepted by matching + verification.
  long prior_refined = 0;  ///< Of which: found by refinement from the prediction (no features).
  long online_full_optimizations = 0;  ///< After closures correcting beyond the gate floor.
  long prior_searches = 0;  ///< Correlative searches around the prediction (prior_search.hpp).
  /// ... of them second, wide searches (the first found nothing), and the alignments they found.
  long prior_wide_searches = 0;
  long prior_wide_found = 0;
  long prior_ridges = 0;  ///< Of which: aligned as ridges (position along a line unmeasured).
  /// Of which: poorly constrained in the refinement, placed along its weak direction by the
  /// search's distinct peak.
  long prior_weak_by_search = 0;
  /// Waiting appearance matches inside one map confirmed by the key maps around them
  /// (JoinVerifier, loop_verification_travel): loops closed beyond the prior search's reach.
  long verified_loops = 0;
  long accepted = 0;  ///< Loop edges added.
  long rejected_gate = 0;
  /// Prior-based closures refused because they correct more than the path between their key
  /// maps can have drifted (loop_closure::BeyondDrift): look-alikes.
  long closures_beyond_drift = 0;
  long pruned = 0;
  long joins = 0;
  /// Joins refused because their alignments put walls in free space far more often than the
  /// robots contradict themselves (loop_closure/free_space_check.hpp).
  long joins_refused_free_space = 0;
  long odometry_doubtful = 0;   ///< Front-end frames whose odometry increment was implausible.
  long odometry_overruled = 0;  ///< ... of which the scan match replaced the increment.
  long odometry_missing = 0;    ///< Frames without odometry (scan matching alone).
  long wide_searches = 0;       ///< Wide correlative searches of the front ends.
  long poor_matches = 0;        ///< Matches with odometry found poor (front_end.hpp).
  long poor_rescued = 0;        ///< ... of which a wide search overruled the odometry.
  long poor_ambiguous = 0;      ///< ... of which the wide search found look-alike poses (kept).
  /// Matched frames whose scan left one / both translation directions to the prior.
  long degenerate_one = 0;
  long degenerate_both = 0;
  long far_matches = 0;  ///< Scans matched against the larger matching window (front_end.hpp).
  long wall_normal_frames = 0;   ///< Frames judged on the wall normals (a noisy laser).
  long geometry_recomputed = 0;  ///< Key-map distance fields recomputed for alignments.
  /// Refinements short of usable points run again on the preceding key maps' returns, and how
  /// many of them succeeded (loop_closure::RefinementOptions::window_travel).
  long window_refinements = 0;
  long window_refined = 0;
  double seconds_front_end = 0.0;
  double seconds_description = 0.0;
  double seconds_alignment = 0.0;
  double seconds_optimization = 0.0;
  double seconds_final = 0.0;
  double seconds_fusion = 0.0;
  /// CPU time of the worker thread that integrated the key maps (compute.threads >= 2), up to
  /// the end of the log [s]; 0 with one thread.
  double cpu_seconds_worker = 0.0;
  /// How well the two threads kept each other busy (compute.threads >= 2; wall time [s]): the
  /// front end's thread blocked on a full queue of key maps, and the worker waiting for a key
  /// map after its first.
  double seconds_caller_blocked = 0.0;
  double seconds_worker_idle = 0.0;
  double chi2_final = 0.0;
};

struct MapperResult {
  std::vector<std::vector<TrajectoryPose>> trajectories;  ///< Per robot, every scan.
  pose_graph::PoseGraph graph;                            ///< Optimized key-map graph.
  std::vector<int> vertex_robot;                          ///< Robot of each vertex (by vertex id).
  std::vector<int> component_of_robot;  ///< Robots with the same value share one map frame.
  std::vector<ClosureRecord> closures;
  std::vector<JoinRecord> joins;
  /// Fused log-odds grid per map component (index = component value of component_of_robot),
  /// tiled: only the tiles the scans touched hold memory.
  std::vector<TiledGrid<float>> maps;
  /// Per robot: where its laser sits beyond the mounting the front end used, as the data
  /// measure it (scan_matching/mounting_estimate.hpp). Reported only; the mapping used the given
  /// mounting.
  std::vector<scan_matching::MountingResult> mountings;
  MapperStats stats;
};

/// The map so far (Mapper::Snapshot).
struct MapSnapshot {
  Time time;  ///< Time of the latest frame.
  /// Per robot, every scan so far at its current corrected pose (no interpolation between
  /// key maps: each scan follows its key map; scans after the newest key map follow it).
  std::vector<std::vector<TrajectoryPose>> trajectories;
  std::vector<int> component_of_robot;  ///< As MapperResult::component_of_robot.
  /// Log-odds grid per map component: each key map's scans, fused once in the key map's frame
  /// and placed at its current estimate (re-placed only when the estimate moved by more than a
  /// cell). Scans not yet in a key map are not in it.
  std::vector<Grid2D<float>> maps;
  long key_maps_replaced = 0;  ///< Key maps placed again (moved) by this snapshot.
  long key_maps_added = 0;     ///< Key maps placed for the first time by this snapshot.
};

class Mapper {
 public:
  /// `options` must be valid (SlamOptions::Validate). `num_robots` >= 1.
  Mapper(const MapperOptions& options, int num_robots);
  ~Mapper();
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  /// Processes the next frame of robot `robot` (frames of each robot in its log order; robots
  /// interleaved by time as a team would deliver them).
  void AddFrame(int robot, const Frame& frame);
  /// Ends the run: final optimization, corrected poses, fusion. The front ends, the worker
  /// thread and the scratch buffers of the calling thread are released first, so no AddFrame
  /// may follow; the online API below stays valid.
  MapperResult Finish();
  /// Current statistics (also during the run).
  [[nodiscard]] const MapperStats& Stats() const;

  // Online API: valid at any time between calls to AddFrame (and after Finish).
  /// T_map_base of the robot's latest frame in its map frame (the frame of its map component),
  /// nullopt before its first frame.
  [[nodiscard]] std::optional<Pose2> CurrentPose(int robot) const;
  /// T_map_odom: maps the robot's odometry frame (Frame::T_odom_base's) into its map frame,
  /// so that MapToOdom * the latest frame's T_odom_base = CurrentPose (what a ROS node would
  /// publish as map -> odom). Recordings without odometry: the front end's frame stands in.
  /// Identity before the robot's first frame.
  [[nodiscard]] Pose2 MapToOdom(int robot) const;
  /// The robot's map component (robots with the same value share one map frame; numbered as in
  /// MapperResult::component_of_robot).
  [[nodiscard]] int MapComponent(int robot) const;
  /// Trajectories and maps so far. Cost: the scans (poses) plus the key maps that were added or
  /// moved since the last snapshot (fusion).
  MapSnapshot Snapshot();
  /// The events since the last call, oldest first.
  std::vector<MapperEvent> DrainEvents();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gridslam::pipeline
