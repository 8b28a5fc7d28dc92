// Options of the graph-SLAM mapper (docs/design.md §1, §1.6-1.8): how key maps become a pose graph,
// how it is optimized online and at the end, and how every scan's corrected pose follows.
#pragma once

#include <string>

#include "gridslam/common/options.hpp"
#include "gridslam/description/description_options.hpp"
#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/loop_closure/loop_closure_options.hpp"
#include "gridslam/matching/align.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/scan_matching/front_end_options.hpp"

namespace gridslam::pipeline {

struct GraphOptions {
  /// Sequential edges between consecutive key maps of a robot: "front_end" (the front end's
  /// relative pose, always) or "alignment" (feature alignment + refinement when it is verified
  /// and agrees with the front end, else the front end's).
  std::string sequential_edges = "front_end";
  /// Sequential edge standard deviations: a floor plus a part per metre between the key maps.
  double sequential_sigma_xy = 0.01;            ///< [m]
  double sequential_sigma_xy_per_m = 0.01;      ///< [m/m]
  double sequential_sigma_theta = 0.002;        ///< [rad]
  double sequential_sigma_theta_per_m = 0.002;  ///< [rad/m]
  /// Weight of a loop edge in the uncertainty distance (docs/design.md §1.6) [m].
  double loop_uncertainty = 0.5;
  /// SGD iterations run after a key map whose accepted closures disagree with the current
  /// estimate by more than online_trigger_xy / online_trigger_theta (online, incremental) [-].
  int online_iterations = 5;
  double online_trigger_xy = 0.05;     ///< [m]
  double online_trigger_theta = 0.01;  ///< [rad]
  /// After a key map whose accepted prior-based closure corrects the estimate by more than the
  /// gate floor (loop_closure.gate_xy, gate_theta), optimize the whole graph (optimizer) instead.
  /// Off by default: it lets look-alike rooms of the simulated "ambiguous" world in (seed 1:
  /// 0.072 -> 0.486 m) and changes fr-clinic and intel by less than 1 % (docs/results.md).
  bool optimize_large_corrections = false;
  /// Final optimization of the whole graph: gn, lm, sgd+gn, sgd or none.
  std::string final_method = "gn";
  /// Rounds of final optimization + pruning of inconsistent loop edges [-].
  int prune_rounds = 3;
  /// Corrected scan poses interpolate the drift correction between neighbouring key maps.
  bool interpolate_corrections = true;

  template <class V>
  void Visit(V& v) {
    v("sequential_edges", sequential_edges,
      "Sequential edges: front_end (relative pose of the front end) or alignment");
    v("sequential_sigma_xy", sequential_sigma_xy, "Sequential edge std, translation floor [m]");
    v("sequential_sigma_xy_per_m", sequential_sigma_xy_per_m,
      "... plus this per metre between the key maps [m/m]");
    v("sequential_sigma_theta", sequential_sigma_theta,
      "Sequential edge std, rotation floor [rad]");
    v("sequential_sigma_theta_per_m", sequential_sigma_theta_per_m,
      "... plus this per metre [rad/m]");
    v("loop_uncertainty", loop_uncertainty,
      "Weight of a loop edge in the uncertainty distance of the gates [m]");
    v("online_iterations", online_iterations,
      "SGD iterations after a key map with accepted closures that move the estimate [-]");
    v("online_trigger_xy", online_trigger_xy,
      "Optimize online when a closure differs from the estimate by more than this [m] ...");
    v("online_trigger_theta", online_trigger_theta, "... or by more than this [rad]");
    v("optimize_large_corrections", optimize_large_corrections,
      "Optimize the whole graph after closures correcting beyond the gate floor");
    v("final_method", final_method, "Final optimization: gn, lm, sgd+gn, sgd or none");
    v("prune_rounds", prune_rounds, "Rounds of final optimization and loop-edge pruning [-]");
    v("interpolate_corrections", interpolate_corrections,
      "Interpolate the drift correction of scans between neighbouring key maps");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(sequential_edges == "front_end" || sequential_edges == "alignment",
                "graph.sequential_edges is front_end or alignment"));
    GRIDSLAM_RETURN_IF_ERROR(Require(sequential_sigma_xy > 0.0 && sequential_sigma_theta > 0.0,
                                     "graph sequential sigmas > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(sequential_sigma_xy_per_m >= 0.0 && sequential_sigma_theta_per_m >= 0.0,
                "graph sequential sigma growth >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(loop_uncertainty >= 0.0, "graph.loop_uncertainty >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(online_iterations >= 0, "graph.online_iterations >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(final_method == "gn" || final_method == "lm" ||
                                         final_method == "sgd+gn" || final_method == "sgd" ||
                                         final_method == "none",
                                     "graph.final_method is gn, lm, sgd+gn, sgd or none"));
    return Require(prune_rounds >= 1, "graph.prune_rounds >= 1");
  }
};

/// How the mapper uses the machine (issue 19). None of these changes the results: a run with any
/// number of threads and any cache size gives the same output, bit for bit.
struct ComputeOptions {
  /// Threads of the mapper, the caller's included: 1 runs everything on the caller's thread; 2
  /// or more describe and integrate key maps (graph, loop closures, optimization) on a worker
  /// thread while the caller's thread runs the front end; 0 = the number of cores, at most 2 [-].
  int threads = 0;
  /// Key-map distance fields kept in memory for loop-closure alignments (about 0.4 MB each for
  /// 15 m key maps at 5 cm); the others are recomputed from the key map's cells when needed [-].
  int key_map_cache = 256;

  template <class V>
  void Visit(V& v) {
    v("threads", threads,
      "Threads of the mapper, the caller's included: 1 = all on one thread, 2 = key maps on a "
      "worker thread; 0 = the number of cores, at most 2 (same results for any value) [-]");
    v("key_map_cache", key_map_cache,
      "Key-map distance fields kept for loop-closure alignments (about 0.4 MB each); others are "
      "recomputed when needed [-]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(threads >= 0 && threads <= 64, "compute.threads in [0, 64]"));
    return Require(key_map_cache >= 1, "compute.key_map_cache >= 1");
  }
  /// `threads` with 0 resolved.
  [[nodiscard]] int Threads() const;
};

/// What the Mapper needs of the configuration: the sections of SlamOptions it uses (documented
/// there; SlamOptions::Mapper() builds it). Each is validated by SlamOptions::Validate().
struct MapperOptions {
  scan_matching::FrontEndOptions front_end;       ///< Scan matching, local map, key maps.
  description::DescriptionOptions description;    ///< Key-map description (DT + SURF).
  matching::AlignOptions matching;                ///< Key-map alignment.
  pose_graph::OptimizerOptions optimizer;         ///< Pose-graph optimization.
  loop_closure::LoopClosureOptions loop_closure;  ///< Loop-closure search and gates.
  GraphOptions graph;                             ///< Building and optimizing the graph.
  fusion::FusionOptions fusion;                   ///< Global map fusion.
  ComputeOptions compute;                         ///< Threads and memory.
};

}  // namespace gridslam::pipeline
