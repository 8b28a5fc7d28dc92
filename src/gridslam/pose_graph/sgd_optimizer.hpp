// Stochastic gradient descent on a tree parameterization of the pose graph: Olson, Leonard,
// Teller, ICRA 2006, as refined by Grisetti, Stachniss, Grzonka, Burgard, RSS 2007 (TORO 2-D),
// with the online learning-rate schedule of Grisetti, Stachniss, Burgard, T-ITS 2009
// (docs/method.md §4; the paper's optimizer, §1.5.5).
//
// Each connected component gets a spanning tree rooted at its fixed vertices (one anchor per
// component); all roots hang from one virtual root at the map origin. A vertex's parameter is its
// pose minus its parent's pose, component-wise in the global frame (§4.2 item 2). Edges are
// processed one at a time, ordered by the level of the top node of their tree path (§4.2 item 4).
// For an edge, the residual r = (p_i (+) Z) - p_j (theta wrapped) weighted by W = R Omega R^T
// gives the gradient d = 2 W r; the total correction beta = l * alpha * d, with the per-dimension
// learning rate alpha = 1 / (gamma * t), is clamped to |r| and split over the path nodes in
// proportion to 1 / M (M = Jacobi preconditioner: the summed information of the edges whose path
// contains the node), with opposite signs on the two branches (§4.2 item 5). Unlike TORO, the
// default variant rotates the full information matrix (x-y-theta correlations included) into the
// global frame with the predicted pose's rotation, so r^T W r is exactly the g2o chi^2 of the
// edge; and the spanning tree is chosen per graph for the shortest total path length.
//
// Incremental use (§4.2 item 8, §4.3): AddVertex/AddEdge between Iterate() calls. A new vertex
// joined by its first edge becomes a leaf of that edge's other end and is initialized from the
// edge. Every node keeps its own schedule t_n (per-node learning rates, Grisetti 2009): it grows by
// one per iteration and is not restarted; a new edge that is inconsistent (chi^2 above a
// threshold) lowers t_n on its path in proportion, so only the affected part speeds up. Joining
// two components moves the one without a fixed vertex rigidly onto the new edge. With
// SgdOptions::rebuild_tree the tree of the graph as it grew is rebuilt before the next iteration
// once a loop edge has been added, so that the closures' paths stay short.
//
// Not thread-safe; one optimizer per graph.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gridslam/pose_graph/pose_graph.hpp"
#include "gridslam/pose_graph/sgd_options.hpp"

namespace gridslam::pose_graph {

class SgdOptimizer {
 public:
  explicit SgdOptimizer(SgdOptions options = {});
  /// Starts from a copy of `graph` (its poses are the initial guess).
  SgdOptimizer(const PoseGraph& graph, SgdOptions options);

  /// Adds a vertex with an initial guess. A non-fixed vertex whose first edge joins it to
  /// another component is re-initialized from that edge.
  void AddVertex(int id, const Pose2& T_map_v, bool fixed = false);
  /// Adds an edge between existing vertices (checked), with PoseGraph::AddEdge's contract.
  void AddEdge(int from, int to, const Pose2& T_i_j, const Eigen::Matrix3d& information);

  /// Runs `n` iterations (one preconditioner update and one sweep over all edges each). With
  /// options.rebuild_tree, a loop closed since the tree was built rebuilds it first.
  void Iterate(int n = 1);

  /// The graph with the current estimates.
  [[nodiscard]] const PoseGraph& graph() const;
  /// g2o chi^2 at the current estimates.
  [[nodiscard]] double Chi2() const;
  /// Iterations run so far.
  [[nodiscard]] int iterations() const { return iterations_; }
  /// Sum over edges of the number of tree edges on their path (cost of one iteration).
  [[nodiscard]] long TotalPathLength() const;

 private:
  struct SgdEdge {
    int v1 = 0;  ///< Vertex index of the edge's "from" end.
    int v2 = 0;  ///< Vertex index of the edge's "to" end.
    Eigen::Vector3d z = Eigen::Vector3d::Zero();
    Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
    int top = -1;  ///< Lowest common ancestor (-1: the virtual root).
    int length = 0;
    double cos_z = 1.0;  ///< cos and sin of z's angle.
    double sin_z = 0.0;
  };
  static SgdEdge MakeEdge(int v1, int v2, const Pose2& z, const Eigen::Matrix3d& information);

  // Structure (sgd_optimizer.cpp).
  void Rebuild();
  void BuildTree();
  void BuildTree(const std::string& kind);
  void FillEdgeInfo(SgdEdge& edge) const;
  void InsertSorted(int edge_index);
  void AttachLeaf(int leaf, int parent, const Eigen::Vector3d& T_parent_leaf);
  void RaiseRates(const SgdEdge& edge);
  [[nodiscard]] Eigen::Vector3d ParamFromPoses(int v) const;
  [[nodiscard]] Eigen::Vector3d PoseFromParam(int v) const;
  void RecomputePoses();
  void SyncGraph() const;
  int CollectBranch(int v, int top, std::vector<int>& nodes) const;
  [[nodiscard]] int Root(int v) const;

  /// An edge's tree path as ranges of path_nodes_ and path_free_: its first branch (v1 up to,
  /// not including, the top) is [begin, split), its second (v2 up to the top) [split, end); the
  /// free vertices of both, in the same order, [free_begin, free_split) and [free_split,
  /// free_end).
  struct EdgePath {
    std::uint32_t begin = 0;
    std::uint32_t split = 0;
    std::uint32_t end = 0;
    std::uint32_t free_begin = 0;
    std::uint32_t free_split = 0;
    std::uint32_t free_end = 0;
  };

  // One iteration (sgd_update.cpp).
  void IndexPaths();
  void ComputePreconditioner();
  void UpdateEdge(const SgdEdge& edge, const EdgePath& path);

  SgdOptions options_;
  mutable PoseGraph graph_;
  mutable bool graph_synced_ = true;
  bool tree_stale_ = false;  ///< An edge closed a loop since the tree was built.
  int iterations_ = 0;

  // Per vertex index.
  std::vector<Eigen::Vector3d> pose_;   ///< (x, y, theta) in the map, theta not wrapped.
  std::vector<Eigen::Vector3d> param_;  ///< pose - parent pose (roots: their pose).
  std::vector<Eigen::Vector3d> precond_;
  std::vector<double> age_;  ///< Per-node schedule t_n (learning rate 1 / (gamma t_n)).
  std::vector<int> parent_;  ///< Parent vertex index, -1 for roots.
  std::vector<int> level_;
  std::vector<bool> fixed_;
  std::vector<bool> attached_;  ///< Has at least one edge.
  std::vector<int> order_;      ///< Vertices in tree order (parents first).

  std::vector<SgdEdge> edges_;
  std::vector<int> sorted_;  ///< Edge indices by ascending level of their top.
  Eigen::Vector3d gamma_ = Eigen::Vector3d::Ones();

  /// precond_ inverted per dimension (set with it, once per iteration).
  std::vector<Eigen::Vector3d> inv_precond_;
  bool toro_ = false;  ///< options_.variant == "toro".

  // The edges' tree paths, walked once per tree instead of once per edge and iteration: a path
  // changes only when the tree is rebuilt (Rebuild clears them). A leaf attached later is on no
  // earlier edge's path, and only such a leaf changes from fixed to free outside Rebuild.
  std::vector<EdgePath> paths_;  ///< Per edge index; the edges beyond its size are not indexed.
  std::vector<int> path_nodes_;
  std::vector<int> path_free_;

  // Scratch space.
  std::vector<int> branch1_;  ///< RaiseRates' branches.
  std::vector<int> branch2_;
  std::vector<double> shares_;  ///< t_edge / t_n of an edge's free vertices.
};

}  // namespace gridslam::pose_graph
