// One SGD iteration of SgdOptimizer: the Jacobi preconditioner and the per-edge update
// (docs/method.md §4.2 item 5).
#include <algorithm>
#include <cmath>
#include <limits>

#include "gridslam/common/angles.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"

namespace gridslam::pose_graph {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

// diag(R Omega R^T) with R = diag(R2(theta), 1), (c, s) = (cos, sin) theta: the information of
// an error expressed in a frame rotated by theta, here the global frame.
Eigen::Vector3d RotatedDiagonal(const Eigen::Matrix3d& information, double c, double s) {
  const double a = information(0, 0);
  const double b = information(0, 1);
  const double d = information(1, 1);
  return {c * c * a - 2.0 * c * s * b + s * s * d, s * s * a + 2.0 * c * s * b + c * c * d,
          information(2, 2)};
}

// R Omega R^T r, without forming the rotated matrix.
Eigen::Vector3d RotatedProduct(const Eigen::Matrix3d& information, double c, double s,
                               const Eigen::Vector3d& r) {
  const Eigen::Vector3d local(c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z());
  const Eigen::Vector3d v = information * local;
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

}  // namespace

void SgdOptimizer::Iterate(int n) {
  if (n > 0 && tree_stale_ && options_.rebuild_tree) {
    Rebuild();  // keeps every node's age: the schedule goes on
  }
  IndexPaths();
  graph_synced_ = n <= 0 && graph_synced_;  // graph() copies the poses when it is next read.
  for (int it = 0; it < n; ++it) {
    ComputePreconditioner();
    for (double& age : age_) {
      age += 1.0;  // TORO increments its iteration count before the sweep.
    }
    for (const int k : sorted_) {
      UpdateEdge(edges_[U(k)], paths_[U(k)]);
    }
    RecomputePoses();
    ++iterations_;
  }
}

void SgdOptimizer::IndexPaths() {
  const auto at = [](const std::vector<int>& v) { return static_cast<std::uint32_t>(v.size()); };
  for (std::size_t k = paths_.size(); k < edges_.size(); ++k) {
    const SgdEdge& edge = edges_[k];
    EdgePath path;
    path.begin = at(path_nodes_);
    path.free_begin = at(path_free_);
    const auto walk = [&](int start) {
      for (int v = start; v != edge.top; v = parent_[U(v)]) {
        path_nodes_.push_back(v);
        if (!fixed_[U(v)]) {
          path_free_.push_back(v);
        }
      }
    };
    walk(edge.v1);
    path.split = at(path_nodes_);
    path.free_split = at(path_free_);
    walk(edge.v2);
    path.end = at(path_nodes_);
    path.free_end = at(path_free_);
    paths_.push_back(path);
  }
}

void SgdOptimizer::ComputePreconditioner() {
  constexpr double kMax = std::numeric_limits<double>::max();
  gamma_ = Eigen::Vector3d::Constant(kMax);
  std::fill(precond_.begin(), precond_.end(), Eigen::Vector3d::Zero());
  const bool toro = toro_;
  for (std::size_t k = 0; k < edges_.size(); ++k) {
    const SgdEdge& edge = edges_[k];
    const EdgePath& path = paths_[k];
    // TORO rotates by the measurement's own angle; "g2o" by the predicted pose's.
    const double theta = toro ? edge.z.z() : pose_[U(edge.v1)].z() + edge.z.z();
    const Eigen::Vector3d w = RotatedDiagonal(edge.information, std::cos(theta), std::sin(theta));
    for (std::uint32_t f = path.free_begin; f < path.free_end; ++f) {
      precond_[U(path_free_[f])] += w;
    }
    if (path.free_end > path.free_begin) {
      gamma_ = gamma_.cwiseMin(w);
    }
  }
  for (int d = 0; d < 3; ++d) {
    if (gamma_[d] == kMax || gamma_[d] <= 0.0) {
      gamma_[d] = 1.0;  // No free constraint, or a zero information entry somewhere.
    }
  }
  inv_precond_.resize(precond_.size());
  for (std::size_t v = 0; v < precond_.size(); ++v) {
    inv_precond_[v] = precond_[v].cwiseInverse();
  }
}

void SgdOptimizer::UpdateEdge(const SgdEdge& edge, const EdgePath& path) {
  const std::size_t length = path.free_end - path.free_begin;
  if (length == 0) {
    return;  // Both ends fixed.
  }
  // Poses relative to the stored pose of the top (TORO's getPose): the top's pose plus the
  // parameters up each branch, summed from the end vertex upwards.
  const int* const nodes = path_nodes_.data();
  const int* const free = path_free_.data() + path.free_begin;
  const std::size_t split = path.free_split - path.free_begin;
  const Eigen::Vector3d base =
      edge.top < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(pose_[U(edge.top)]);
  Eigen::Vector3d p1 = base;
  for (std::uint32_t i = path.begin; i < path.split; ++i) {
    p1 += param_[U(nodes[i])];
  }
  Eigen::Vector3d p2 = base;
  for (std::uint32_t i = path.split; i < path.end; ++i) {
    p2 += param_[U(nodes[i])];
  }
  // Residual r = (p1 (+) Z) - p2 in the global frame, theta wrapped.
  const double c1 = std::cos(p1.z());
  const double s1 = std::sin(p1.z());
  const Eigen::Vector3d r(p1.x() + c1 * edge.z.x() - s1 * edge.z.y() - p2.x(),
                          p1.y() + s1 * edge.z.x() + c1 * edge.z.y() - p2.y(),
                          NormalizeAngle(p1.z() + edge.z.z() - p2.z()));
  // W = R Omega R^T with R = R(theta_1 + theta_z) ("g2o") or R(theta_1) ("toro").
  const bool toro = toro_;
  const double cw = toro ? c1 : c1 * edge.cos_z - s1 * edge.sin_z;
  const double sw = toro ? s1 : s1 * edge.cos_z + c1 * edge.sin_z;
  const Eigen::Vector3d d = 2.0 * RotatedProduct(edge.information, cw, sw, r);

  // Per-node schedules (Grisetti 2009): the edge uses the fastest rate on its path, t_edge;
  // slower nodes take a proportionally smaller share t_edge / t_n. A node's share is 1 / (M t)
  // per dimension (TORO: 1 / M, all t equal in batch use).
  double t_edge = std::numeric_limits<double>::max();
  for (std::size_t f = 0; f < length; ++f) {
    t_edge = std::min(t_edge, age_[U(free[f])]);
  }
  shares_.resize(length);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (std::size_t f = 0; f < length; ++f) {
    const int v = free[f];
    shares_[f] = t_edge / age_[U(v)];
    total += shares_[f] * inv_precond_[U(v)];
  }
  Eigen::Vector3d beta;
  for (int dim = 0; dim < 3; ++dim) {
    // Total correction l * alpha * d with alpha = 1 / (gamma t), never beyond the residual.
    beta[dim] = static_cast<double>(length) * d[dim] / (gamma_[dim] * t_edge);
    if (std::abs(beta[dim]) > std::abs(r[dim])) {
      beta[dim] = r[dim];
    }
    beta[dim] = total[dim] > 0.0 && std::isfinite(total[dim]) ? beta[dim] / total[dim] : 0.0;
  }
  for (int dir = 0; dir < 2; ++dir) {
    // Move p1 towards p2 and p2 towards p1 (+) Z: the first branch's shares are negated (a
    // negated quotient is the quotient of the negated dividend, exactly).
    const bool first = dir == 0;
    const std::size_t begin = first ? 0 : split;
    const std::size_t end = first ? split : length;
    for (std::size_t f = begin; f < end; ++f) {
      const int v = free[f];
      const double share = first ? -shares_[f] : shares_[f];
      param_[U(v)] += share * beta.cwiseProduct(inv_precond_[U(v)]);
    }
    // Poses along the branch, from the top down (TORO's updatePoseChain; PoseFromParam).
    const std::uint32_t lo = first ? path.begin : path.split;
    const std::uint32_t hi = first ? path.split : path.end;
    for (std::uint32_t i = hi; i > lo; --i) {
      const int v = nodes[i - 1];
      const int p = parent_[U(v)];
      pose_[U(v)] = p < 0 ? param_[U(v)] : Eigen::Vector3d(pose_[U(p)] + param_[U(v)]);
    }
  }
}

}  // namespace gridslam::pose_graph
