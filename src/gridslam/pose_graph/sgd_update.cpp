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
  for (int it = 0; it < n; ++it) {
    SyncGraph();
    graph_synced_ = false;
    ComputePreconditioner();
    for (double& age : age_) {
      age += 1.0;  // TORO increments its iteration count before the sweep.
    }
    for (const int k : sorted_) {
      UpdateEdge(edges_[U(k)]);
    }
    RecomputePoses();
    ++iterations_;
  }
}

void SgdOptimizer::ComputePreconditioner() {
  constexpr double kMax = std::numeric_limits<double>::max();
  gamma_ = Eigen::Vector3d::Constant(kMax);
  std::fill(precond_.begin(), precond_.end(), Eigen::Vector3d::Zero());
  const bool toro = toro_;
  for (const SgdEdge& edge : edges_) {
    // TORO rotates by the measurement's own angle; "g2o" by the predicted pose's.
    const double theta = toro ? edge.z.z() : pose_[U(edge.v1)].z() + edge.z.z();
    const Eigen::Vector3d w = RotatedDiagonal(edge.information, std::cos(theta), std::sin(theta));
    bool any_free = false;
    for (const int start : {edge.v1, edge.v2}) {
      for (int v = start; v != edge.top; v = parent_[U(v)]) {
        if (!fixed_[U(v)]) {
          precond_[U(v)] += w;
          any_free = true;
        }
      }
    }
    if (any_free) {
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

void SgdOptimizer::UpdateEdge(const SgdEdge& edge) {
  // Poses relative to the stored pose of the top (TORO's getPose): the top's pose plus the
  // parameters up each branch (CollectBranch's walk, summed as it goes), and the free vertices of
  // both branches in order (the loops below visit only them).
  const Eigen::Vector3d base =
      edge.top < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(pose_[U(edge.top)]);
  free_.clear();
  Eigen::Vector3d p1 = base;
  branch1_.clear();
  for (int n = edge.v1; n != edge.top; n = parent_[U(n)]) {
    branch1_.push_back(n);
    p1 += param_[U(n)];
    if (!fixed_[U(n)]) {
      free_.push_back(n);
    }
  }
  const std::size_t split = free_.size();
  Eigen::Vector3d p2 = base;
  branch2_.clear();
  for (int n = edge.v2; n != edge.top; n = parent_[U(n)]) {
    branch2_.push_back(n);
    p2 += param_[U(n)];
    if (!fixed_[U(n)]) {
      free_.push_back(n);
    }
  }
  const int length = static_cast<int>(free_.size());
  if (length == 0) {
    return;  // Both ends fixed.
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
  // slower nodes take a proportionally smaller share. A node's share is 1 / (M t) per
  // dimension (TORO: 1 / M, all t equal in batch use).
  double t_edge = std::numeric_limits<double>::max();
  for (const int v : free_) {
    t_edge = std::min(t_edge, age_[U(v)]);
  }
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (const int v : free_) {
    total += (t_edge / age_[U(v)]) * inv_precond_[U(v)];
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
    const auto& branch = dir == 0 ? branch1_ : branch2_;
    const double sign = dir == 0 ? -1.0 : 1.0;  // Move p1 towards p2 and p2 towards p1 (+) Z.
    const std::size_t begin = dir == 0 ? 0 : split;
    const std::size_t end = dir == 0 ? split : free_.size();
    for (std::size_t f = begin; f < end; ++f) {
      const int v = free_[f];
      param_[U(v)] += (sign * t_edge / age_[U(v)]) * beta.cwiseProduct(inv_precond_[U(v)]);
    }
    // Poses along the branch, from the top down (TORO's updatePoseChain; PoseFromParam).
    for (auto it = branch.rbegin(); it != branch.rend(); ++it) {
      const int p = parent_[U(*it)];
      pose_[U(*it)] = p < 0 ? param_[U(*it)] : Eigen::Vector3d(pose_[U(p)] + param_[U(*it)]);
    }
  }
}

}  // namespace gridslam::pose_graph
