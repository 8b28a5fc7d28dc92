// Options of the SGD pose-graph optimizer (Olson et al. 2006; Grisetti et al. 2007, TORO 2-D;
// Grisetti et al. 2009; reconstruction.md §4.1-4.3). See sgd_optimizer.hpp for the algorithm.
#pragma once

#include <string>

#include "gridslam/common/options.hpp"

namespace gridslam::pose_graph {

struct SgdOptions {
  /// Parameterization and update rule:
  ///  - "relative": a vertex's parameter is its pose in its parent's frame (SE(2) tree, as TORO
  ///    3-D); an edge's error is computed exactly in the frame of its path's top; the rotational
  ///    residual is distributed first (rotating whole subtrees), then the translational one
  ///    (Grisetti et al. 2009). Rotation-invariant preconditioner and learning rates.
  ///  - "global": TORO 2-D's component-wise global parameters, with the information rotated by the
  ///    predicted pose's rotation R(theta_i + theta_ij), i.e. the exact g2o chi^2.
  ///  - "toro": TORO 2-D exactly (R(theta_i) for the update, the measurement's rotation for the
  ///    preconditioner); reproduces TORO's figures.
  std::string variant = "relative";
  /// Spanning tree of each component: "toro" (TORO's buildSimpleTree: parent = the smallest-id
  /// lower neighbour), "bfs" (breadth-first from the anchors) or "chain" (Olson's odometry chain).
  std::string tree = "toro";
  /// Incremental mode (Grisetti et al. 2009): a new edge whose chi^2 exceeds this raises the
  /// learning rate of the nodes on its path in proportion; consistent edges leave the schedule
  /// alone [chi^2, 3 dof; 7.81 = 95 %].
  double incremental_chi2_threshold = 7.81;

  template <class V>
  void Visit(V& v) {
    v("variant", variant,
      "relative (SE(2) tree, rotation then translation), global (TORO 2-D with exact g2o "
      "weights) or toro (TORO 2-D as published)");
    v("tree", tree, "Spanning tree: toro (smallest-id parent), bfs or chain (odometry)");
    v("incremental_chi2_threshold", incremental_chi2_threshold,
      "New edges above this chi^2 raise the learning rates on their path [chi^2]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(variant == "relative" || variant == "global" || variant == "toro",
                "optimizer.sgd.variant is relative, global or toro"));
    GRIDSLAM_RETURN_IF_ERROR(Require(tree == "bfs" || tree == "chain" || tree == "toro",
                                     "optimizer.sgd.tree is toro, bfs or chain"));
    return Require(incremental_chi2_threshold > 0.0,
                   "optimizer.sgd.incremental_chi2_threshold > 0");
  }
};

}  // namespace gridslam::pose_graph
