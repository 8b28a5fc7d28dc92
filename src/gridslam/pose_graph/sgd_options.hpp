// Options of the SGD pose-graph optimizer (Olson et al. 2006; Grisetti et al. 2007, TORO 2-D;
// Grisetti et al. 2009; docs/method.md §4.1-4.3). See sgd_optimizer.hpp for the algorithm.
#pragma once

#include <string>

#include "gridslam/common/options.hpp"

namespace gridslam::pose_graph {

struct SgdOptions {
  /// Update rule:
  ///  - "g2o": TORO 2-D's update with the information rotated into the global frame by the
  ///    predicted pose's rotation R(theta_i + theta_ij), which makes r^T W r exactly the g2o chi^2
  ///    of the edge, and a preconditioner from the current poses;
  ///  - "toro": TORO 2-D as published (R(theta_i) for the update, the measurement's own rotation
  ///    for the preconditioner); reproduces TORO's figures.
  std::string variant = "g2o";
  /// Spanning tree of each component: "auto" (whichever of toro and bfs has the smaller total
  /// path length, i.e. the cheaper iteration; on the shared graphs also the better one), "toro"
  /// (TORO's buildSimpleTree: parent = the smallest-id lower neighbour), "bfs" (breadth-first
  /// from the anchors) or "chain" (Olson's odometry chain).
  std::string tree = "auto";
  /// Incremental mode (Grisetti et al. 2009): a new edge whose chi^2 exceeds this raises the
  /// learning rate of the nodes on its path in proportion; consistent edges leave the schedule
  /// alone [chi^2, 3 dof; 7.81 = 95 %].
  double incremental_chi2_threshold = 7.81;
  /// Incremental mode: the first Iterate() after an edge that closes a loop builds the spanning
  /// tree again for the whole graph (as `tree` says), keeping every node's schedule t_n. A tree
  /// grown leaf by leaf is the robot's path, on which a closure's path runs around the whole loop:
  /// an iteration then costs the sum of the loops' lengths, which grows with the square of a long
  /// run. Off by default: the online mapper's corrections then take effect at once, which helps
  /// large loops but lets the first group of a look-alike place win (docs/optimizer.md, "Online:
  /// the tree of the current graph").
  bool rebuild_tree = false;

  template <class V>
  void Visit(V& v) {
    v("variant", variant, "g2o (TORO 2-D update on the exact g2o error) or toro (as published)");
    v("tree", tree,
      "Spanning tree: auto (shorter of toro/bfs), toro (smallest-id parent), bfs or chain");
    v("incremental_chi2_threshold", incremental_chi2_threshold,
      "New edges above this chi^2 raise the learning rates on their path [chi^2]");
    v("rebuild_tree", rebuild_tree,
      "Incremental mode: build the spanning tree again after edges that close loops");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(variant == "g2o" || variant == "toro", "optimizer.sgd.variant is g2o or toro"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(tree == "auto" || tree == "bfs" || tree == "chain" || tree == "toro",
                "optimizer.sgd.tree is auto, toro, bfs or chain"));
    return Require(incremental_chi2_threshold > 0.0,
                   "optimizer.sgd.incremental_chi2_threshold > 0");
  }
};

}  // namespace gridslam::pose_graph
