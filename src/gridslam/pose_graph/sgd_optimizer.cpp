#include "gridslam/pose_graph/sgd_optimizer.hpp"

#include <algorithm>
#include <cmath>

#include "gridslam/common/check.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/spanning_tree.hpp"

namespace gridslam::pose_graph {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

// a (+) b for (x, y, theta) vectors; theta adds without wrapping.
Eigen::Vector3d Compose(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::cos(a.z());
  const double s = std::sin(a.z());
  return {a.x() + c * b.x() - s * b.y(), a.y() + s * b.x() + c * b.y(), a.z() + b.z()};
}

// z^-1 for an (x, y, theta) vector.
Eigen::Vector3d Invert(const Eigen::Vector3d& z) {
  const double c = std::cos(z.z());
  const double s = std::sin(z.z());
  return {-(c * z.x() + s * z.y()), s * z.x() - c * z.y(), -z.z()};
}

}  // namespace

SgdOptimizer::SgdOptimizer(SgdOptions options) : options_(std::move(options)) {
  GRIDSLAM_CHECK(options_.Validate().ok()) << options_.Validate().error().ToString();
  toro_ = options_.variant == "toro";
}

SgdOptimizer::SgdOptimizer(const PoseGraph& graph, SgdOptions options)
    : SgdOptimizer(std::move(options)) {
  graph_ = graph;
  const int n = static_cast<int>(graph_.num_vertices());
  for (int v = 0; v < n; ++v) {
    pose_.push_back(graph_.vertex(v).T_map_v.ToVector());
    attached_.push_back(!graph_.Incidence()[U(v)].empty());
  }
  for (int k = 0; k < static_cast<int>(graph_.num_edges()); ++k) {
    const Edge& e = graph_.edge(k);
    edges_.push_back(MakeEdge(graph_.FromIndex(k), graph_.ToIndex(k), e.T_i_j, e.information));
  }
  Rebuild();
}

SgdOptimizer::SgdEdge SgdOptimizer::MakeEdge(int v1, int v2, const Pose2& z,
                                             const Eigen::Matrix3d& information) {
  SgdEdge edge;
  edge.v1 = v1;
  edge.v2 = v2;
  edge.z = z.ToVector();
  edge.information = information;
  edge.cos_z = std::cos(z.theta());
  edge.sin_z = std::sin(z.theta());
  return edge;
}

void SgdOptimizer::AddVertex(int id, const Pose2& T_map_v, bool fixed) {
  SyncGraph();
  const int v = graph_.AddVertex(id, T_map_v, fixed);
  pose_.push_back(T_map_v.ToVector());
  param_.push_back(pose_.back());
  precond_.push_back(Eigen::Vector3d::Zero());
  age_.push_back(1.0);
  parent_.push_back(-1);
  level_.push_back(0);
  fixed_.push_back(true);  // An isolated vertex anchors its own component until joined.
  attached_.push_back(false);
  order_.push_back(v);
}

void SgdOptimizer::AddEdge(int from, int to, const Pose2& T_i_j,
                           const Eigen::Matrix3d& information) {
  SyncGraph();
  const int k = graph_.AddEdge(from, to, T_i_j, information);
  const int i = graph_.FromIndex(k);
  const int j = graph_.ToIndex(k);
  edges_.push_back(MakeEdge(i, j, T_i_j, information));
  const SgdEdge& edge = edges_.back();
  const bool new_i = !attached_[U(i)] && !graph_.vertex(i).fixed;
  const bool new_j = !attached_[U(j)] && !graph_.vertex(j).fixed;
  if (attached_[U(i)] != attached_[U(j)] && (new_i || new_j)) {
    // A new vertex joined by its first edge: a leaf of the other end, initialized from the edge
    // (TORO's addIncrementalEdge / initializeFromParentEdge).
    if (new_j) {
      AttachLeaf(j, i, edge.z);
    } else {
      AttachLeaf(i, j, Invert(edge.z));
    }
    FillEdgeInfo(edges_.back());
    InsertSorted(k);
    return;
  }
  const int root_i = Root(i);
  const int root_j = Root(j);
  const bool auto_i = !graph_.vertex(root_i).fixed;
  const bool auto_j = !graph_.vertex(root_j).fixed;
  attached_[U(i)] = true;
  attached_[U(j)] = true;
  if (root_i == root_j || (!auto_i && !auto_j)) {
    // One tree, or two trees anchored at fixed vertices (the path meets at the virtual root).
    FillEdgeInfo(edges_.back());
    InsertSorted(k);
    RaiseRates(edges_.back());  // on the loop's path in the tree as it grew
    tree_stale_ = true;
    return;
  }
  // Two components join, at least one of them anchored only by our automatic choice: move that
  // one rigidly so that the new edge holds, then rebuild the trees (rare: robots meeting).
  const int moved_root = auto_j ? root_j : root_i;
  const Pose2 X_i = Pose2::FromVector(pose_[U(i)]);
  const Pose2 X_j = Pose2::FromVector(pose_[U(j)]);
  // T X_j = X_i Z when j's side moves, T X_i = X_j Z^-1 when i's side moves.
  const Pose2 T = auto_j ? X_i * T_i_j * X_j.Inverse() : X_j * T_i_j.Inverse() * X_i.Inverse();
  std::vector<bool> moved(graph_.num_vertices(), false);
  for (const int v : order_) {  // Parents come first.
    const int p = parent_[U(v)];
    moved[U(v)] = v == moved_root || (p >= 0 && moved[U(p)]);
    if (moved[U(v)]) {
      const Eigen::Vector3d x = Compose(T.ToVector(), pose_[U(v)]);
      pose_[U(v)] = x;
    }
  }
  Rebuild();
}

void SgdOptimizer::AttachLeaf(int leaf, int parent, const Eigen::Vector3d& T_parent_leaf) {
  pose_[U(leaf)] = Compose(pose_[U(parent)], T_parent_leaf);
  parent_[U(leaf)] = parent;
  level_[U(leaf)] = level_[U(parent)] + 1;
  fixed_[U(leaf)] = false;
  param_[U(leaf)] = ParamFromPoses(leaf);
  age_[U(leaf)] = age_[U(parent)];
  attached_[U(leaf)] = true;
  attached_[U(parent)] = true;
  // Parents come first in order_: move the leaf to the end (it was added recently: search from
  // the back).
  const auto it = std::find(order_.rbegin(), order_.rend(), leaf);
  order_.erase(std::next(it).base());
  order_.push_back(leaf);
  graph_synced_ = false;
}

void SgdOptimizer::RaiseRates(const SgdEdge& edge) {
  // Online schedule (Grisetti 2009): an inconsistent new edge speeds up its path.
  const Eigen::Vector3d e = EdgeError(pose_[U(edge.v1)], pose_[U(edge.v2)], edge.z);
  const double chi2 = e.dot(edge.information * e);
  if (chi2 <= options_.incremental_chi2_threshold) {
    return;
  }
  const double factor = options_.incremental_chi2_threshold / chi2;
  CollectBranch(edge.v1, edge.top, branch1_);
  CollectBranch(edge.v2, edge.top, branch2_);
  for (const auto* branch : {&branch1_, &branch2_}) {
    for (const int v : *branch) {
      age_[U(v)] = std::max(1.0, age_[U(v)] * factor);
    }
  }
}

void SgdOptimizer::Rebuild() {
  graph_synced_ = false;
  tree_stale_ = false;
  paths_.clear();  // The tree changes: every path is walked again.
  path_nodes_.clear();
  path_free_.clear();
  SyncGraph();
  fixed_ = EffectiveFixed(graph_);
  BuildTree();
  const std::size_t n = graph_.num_vertices();
  age_.resize(n, 1.0);
  precond_.assign(n, Eigen::Vector3d::Zero());
  param_.resize(n);
  for (const int v : order_) {
    param_[U(v)] = ParamFromPoses(v);
  }
  for (auto& edge : edges_) {
    FillEdgeInfo(edge);
  }
  sorted_.resize(edges_.size());
  for (std::size_t k = 0; k < edges_.size(); ++k) {
    sorted_[k] = static_cast<int>(k);
  }
  std::stable_sort(sorted_.begin(), sorted_.end(), [&](int a, int b) {
    const int ta = edges_[U(a)].top;
    const int tb = edges_[U(b)].top;
    return (ta < 0 ? -1 : level_[U(ta)]) < (tb < 0 ? -1 : level_[U(tb)]);
  });
}

void SgdOptimizer::BuildTree() {
  if (options_.tree != "auto") {
    BuildTree(options_.tree);
    return;
  }
  // The tree with the smaller total path length: cheaper iterations, and on the shared graphs
  // also the lower chi^2 after a given number of iterations (docs/optimizer.md).
  BuildTree("bfs");
  long bfs = 0;
  for (auto& edge : edges_) {
    FillEdgeInfo(edge);
    bfs += edge.length;
  }
  BuildTree("toro");
  long toro = 0;
  for (auto& edge : edges_) {
    FillEdgeInfo(edge);
    toro += edge.length;
  }
  if (bfs < toro) {
    BuildTree("bfs");
  }
}

void SgdOptimizer::BuildTree(const std::string& kind) {
  parent_ = BuildSpanningTree(graph_, fixed_, kind);
  const std::size_t n = graph_.num_vertices();
  std::vector<std::vector<int>> children(n);
  order_.clear();
  for (std::size_t v = 0; v < n; ++v) {
    if (parent_[v] < 0) {
      order_.push_back(static_cast<int>(v));
    } else {
      children[U(parent_[v])].push_back(static_cast<int>(v));
    }
  }
  level_.assign(n, 0);
  for (std::size_t head = 0; head < order_.size(); ++head) {
    const int v = order_[head];
    for (const int c : children[U(v)]) {
      level_[U(c)] = level_[U(v)] + 1;
      order_.push_back(c);
    }
  }
}

void SgdOptimizer::FillEdgeInfo(SgdEdge& edge) const {
  int a = edge.v1;
  int b = edge.v2;
  int length = 0;
  while (a != b) {
    const int la = a < 0 ? -1 : level_[U(a)];
    const int lb = b < 0 ? -1 : level_[U(b)];
    if (la >= lb) {
      a = parent_[U(a)];
    } else {
      b = parent_[U(b)];
    }
    ++length;
  }
  edge.top = a;
  edge.length = length;
}

void SgdOptimizer::InsertSorted(int edge_index) {
  auto level_of = [&](int k) {
    const int t = edges_[U(k)].top;
    return t < 0 ? -1 : level_[U(t)];
  };
  const int level = level_of(edge_index);
  const auto it = std::upper_bound(sorted_.begin(), sorted_.end(), level,
                                   [&](int l, int k) { return l < level_of(k); });
  sorted_.insert(it, edge_index);
}

int SgdOptimizer::CollectBranch(int v, int top, std::vector<int>& nodes) const {
  nodes.clear();
  int free = 0;
  for (int n = v; n != top; n = parent_[U(n)]) {
    nodes.push_back(n);
    free += fixed_[U(n)] ? 0 : 1;
  }
  return free;
}

int SgdOptimizer::Root(int v) const {
  while (parent_[U(v)] >= 0) {
    v = parent_[U(v)];
  }
  return v;
}

Eigen::Vector3d SgdOptimizer::ParamFromPoses(int v) const {
  const int p = parent_[U(v)];
  return p < 0 ? pose_[U(v)] : Eigen::Vector3d(pose_[U(v)] - pose_[U(p)]);
}

Eigen::Vector3d SgdOptimizer::PoseFromParam(int v) const {
  const int p = parent_[U(v)];
  return p < 0 ? param_[U(v)] : Eigen::Vector3d(pose_[U(p)] + param_[U(v)]);
}

void SgdOptimizer::RecomputePoses() {
  for (const int v : order_) {
    pose_[U(v)] = PoseFromParam(v);
  }
}

void SgdOptimizer::SyncGraph() const {
  if (graph_synced_) {
    return;
  }
  for (int v = 0; v < static_cast<int>(graph_.num_vertices()); ++v) {
    graph_.SetPose(v, Pose2::FromVector(pose_[U(v)]));
  }
  graph_synced_ = true;
}

const PoseGraph& SgdOptimizer::graph() const {
  SyncGraph();
  return graph_;
}

double SgdOptimizer::Chi2() const {
  double chi2 = 0.0;
  for (const SgdEdge& edge : edges_) {
    const Eigen::Vector3d e = EdgeError(pose_[U(edge.v1)], pose_[U(edge.v2)], edge.z);
    chi2 += e.dot(edge.information * e);
  }
  return chi2;
}

long SgdOptimizer::TotalPathLength() const {
  long total = 0;
  for (const SgdEdge& edge : edges_) {
    total += edge.length;
  }
  return total;
}

}  // namespace gridslam::pose_graph
