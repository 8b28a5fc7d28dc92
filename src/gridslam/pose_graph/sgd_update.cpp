// One SGD iteration: the preconditioner and the per-edge updates of SgdOptimizer
// (reconstruction.md §4.2 item 5; the "relative" variant: §4.3, rotation first).
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <Eigen/LU>

#include "gridslam/common/angles.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"

namespace gridslam::pose_graph {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

Eigen::Matrix3d RotateInformation(const Eigen::Matrix3d& information, double theta) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  r(0, 0) = c;
  r(0, 1) = -s;
  r(1, 0) = s;
  r(1, 1) = c;
  return r * information * r.transpose();
}

// Rotation-invariant diagonal weights of an information matrix: the mean translational
// information for x and y, the rotational one for theta.
Eigen::Vector3d InvariantDiagonal(const Eigen::Matrix3d& information) {
  const double xy = 0.5 * (information(0, 0) + information(1, 1));
  return {xy, xy, information(2, 2)};
}

// The smaller eigenvalue of the translational block, and the rotational information.
Eigen::Vector3d InvariantMinimum(const Eigen::Matrix3d& information) {
  const double a = information(0, 0);
  const double b = information(0, 1);
  const double d = information(1, 1);
  const double mean = 0.5 * (a + d);
  const double radius = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
  const double smallest = mean - radius;
  return {smallest, smallest, information(2, 2)};
}

}  // namespace

void SgdOptimizer::Iterate(int n) {
  for (int it = 0; it < n; ++it) {
    SyncGraph();
    graph_synced_ = false;
    ComputePreconditioner();
    static const char* sched = std::getenv("SGD_SCHED");
    static const double sched_factor = std::getenv("SGD_FACTOR") ? std::atof(std::getenv("SGD_FACTOR")) : 1.0;
    if (sched == nullptr || last_chi2_ < 0.0 || Chi2() >= last_chi2_) {
      for (double& age : age_) {
        age = sched == nullptr ? age + 1.0 : (sched[0] == 97 ? age + sched_factor : age * (1.0 + sched_factor));  // TORO increments its iteration count before the sweep.
      }
    }
    if (sched != nullptr) last_chi2_ = Chi2();
    const bool rel = relative();
    for (const int k : sorted_) {
      if (rel) {
        UpdateEdgeRelative(edges_[U(k)]);
      } else {
        UpdateEdgeGlobal(edges_[U(k)]);
      }
    }
    RecomputePoses();
    ++iterations_;
  }
}

void SgdOptimizer::ComputePreconditioner() {
  constexpr double kMax = std::numeric_limits<double>::max();
  gamma_ = Eigen::Vector3d::Constant(kMax);
  std::fill(precond_.begin(), precond_.end(), Eigen::Vector3d::Zero());
  block_ = std::getenv("SGD_BLOCK") != nullptr;
  if (block_) precond_block_.assign(precond_.size(), Eigen::Matrix3d::Zero());
  const bool toro = options_.variant == "toro";
  const bool rel = relative();
  for (const SgdEdge& edge : edges_) {
    Eigen::Vector3d w;
    Eigen::Vector3d smallest;
    if (rel) {
      w = InvariantDiagonal(edge.information);
      smallest = InvariantMinimum(edge.information);
    } else {
      // TORO rotates by the measurement's own angle; "global" by the predicted pose's.
      const double theta = toro ? edge.z.z() : pose_[U(edge.v1)].z() + edge.z.z();
      const Eigen::Matrix3d W = RotateInformation(edge.information, theta);
      w = W.diagonal();
      smallest = w;
      if (block_) {
        for (const int start : {edge.v1, edge.v2}) {
          for (int v = start; v != edge.top; v = parent_[U(v)]) {
            if (!fixed_[U(v)]) precond_block_[U(v)] += W;
          }
        }
      }
    }
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
      gamma_ = gamma_.cwiseMin(smallest);
    }
  }
  for (int d = 0; d < 3; ++d) {
    if (gamma_[d] == kMax || gamma_[d] <= 0.0) {
      gamma_[d] = 1.0;  // No free constraint, or a zero information entry somewhere.
    }
  }
  if (block_) {
    for (auto& m : precond_block_) {
      if (m.diagonal().minCoeff() > 0.0) m = m.inverse().eval();
    }
  }
}

double SgdOptimizer::EdgeSchedule(const SgdEdge& /*edge*/) {
  // Per-node schedules: the edge uses the fastest rate on its path; slower nodes take a
  // proportionally smaller share. Shares are 1 / (M t) per dimension (TORO: 1 / M).
  double t_edge = std::numeric_limits<double>::max();
  for (const auto* branch : {&branch1_, &branch2_}) {
    for (const int v : *branch) {
      if (!fixed_[U(v)]) {
        t_edge = std::min(t_edge, age_[U(v)]);
      }
    }
  }
  share_.clear();
  total_share_.setZero();
  for (const auto* branch : {&branch1_, &branch2_}) {
    for (const int v : *branch) {
      if (fixed_[U(v)]) {
        share_.emplace_back(Eigen::Vector3d::Zero());
        continue;
      }
      Eigen::Vector3d share;
      for (int d = 0; d < 3; ++d) {
        const double m = precond_[U(v)][d];
        share[d] = m > 0.0 ? t_edge / (age_[U(v)] * m) : 0.0;
      }
      share_.push_back(share);
      total_share_ += share;
    }
  }
  return t_edge;
}

void SgdOptimizer::UpdateEdgeGlobal(const SgdEdge& edge) {
  const int free1 = CollectBranch(edge.v1, edge.top, branch1_);
  const int free2 = CollectBranch(edge.v2, edge.top, branch2_);
  const int length = free1 + free2;
  if (length == 0) {
    return;
  }
  // Poses relative to the (possibly stale) stored pose of the top, as TORO's getPose.
  const Eigen::Vector3d base =
      edge.top < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(pose_[U(edge.top)]);
  Eigen::Vector3d p1 = base;
  for (const int v : branch1_) {
    p1 += param_[U(v)];
  }
  Eigen::Vector3d p2 = base;
  for (const int v : branch2_) {
    p2 += param_[U(v)];
  }
  // Residual r = (p1 (+) Z) - p2 in the global frame (§4.2 item 5).
  const double c1 = std::cos(p1.z());
  const double s1 = std::sin(p1.z());
  const Eigen::Vector3d r(p1.x() + c1 * edge.z.x() - s1 * edge.z.y() - p2.x(),
                          p1.y() + s1 * edge.z.x() + c1 * edge.z.y() - p2.y(),
                          NormalizeAngle(p1.z() + edge.z.z() - p2.z()));
  const double theta_w = options_.variant == "toro" ? p1.z() : p1.z() + edge.z.z();
  const Eigen::Vector3d d = 2.0 * (RotateInformation(edge.information, theta_w) * r);
  const double t_edge = EdgeSchedule(edge);
  Eigen::Vector3d beta;
  for (int dim = 0; dim < 3; ++dim) {
    beta[dim] = static_cast<double>(length) * d[dim] / (gamma_[dim] * t_edge);
    if (std::abs(beta[dim]) > std::abs(r[dim])) {
      beta[dim] = r[dim];  // Never over-correct a constraint (TORO's clamp).
    }
  }
  if (block_) {
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (const auto* branch : {&branch1_, &branch2_}) for (const int v : *branch) if (!fixed_[U(v)]) S += (t_edge / age_[U(v)]) * precond_block_[U(v)];
    const Eigen::Vector3d sb = S.inverse() * beta;
    for (int dir = 0; dir < 2; ++dir) {
      const auto& branch = dir == 0 ? branch1_ : branch2_;
      const double sign = dir == 0 ? -1.0 : 1.0;
      for (const int v : branch) if (!fixed_[U(v)]) param_[U(v)] += sign * (t_edge / age_[U(v)]) * (precond_block_[U(v)] * sb);
      for (auto it = branch.rbegin(); it != branch.rend(); ++it) pose_[U(*it)] = PoseFromParam(*it);
    }
    return;
  }
  std::size_t k = 0;
  for (int dir = 0; dir < 2; ++dir) {
    const auto& branch = dir == 0 ? branch1_ : branch2_;
    const double sign = dir == 0 ? -1.0 : 1.0;
    for (const int v : branch) {
      const Eigen::Vector3d& share = share_[k++];
      for (int dim = 0; dim < 3; ++dim) {
        if (total_share_[dim] > 0.0) {
          param_[U(v)][dim] += sign * beta[dim] * share[dim] / total_share_[dim];
        }
      }
    }
    // Poses along the branch, from the top down (TORO's updatePoseChain).
    for (auto it = branch.rbegin(); it != branch.rend(); ++it) {
      pose_[U(*it)] = PoseFromParam(*it);
    }
  }
}

Eigen::Vector3d SgdOptimizer::ComposeBranch(const std::vector<int>& branch,
                                            std::vector<double>* parent_theta) {
  // The pose of the branch's bottom node in the frame of the top: params composed top-down.
  if (parent_theta != nullptr) {
    parent_theta->resize(branch.size());
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t k = branch.size(); k-- > 0;) {
    if (parent_theta != nullptr) {
      (*parent_theta)[k] = p.z();
    }
    const Eigen::Vector3d& q = param_[U(branch[k])];
    const double c = std::cos(p.z());
    const double s = std::sin(p.z());
    p = Eigen::Vector3d(p.x() + c * q.x() - s * q.y(), p.y() + s * q.x() + c * q.y(),
                        p.z() + q.z());
  }
  return p;
}

void SgdOptimizer::UpdateEdgeRelative(const SgdEdge& edge) {
  const int free1 = CollectBranch(edge.v1, edge.top, branch1_);
  const int free2 = CollectBranch(edge.v2, edge.top, branch2_);
  const double length = static_cast<double>(free1 + free2);
  if (free1 + free2 == 0) {
    return;
  }
  const double t_edge = EdgeSchedule(edge);
  // Residual in the frame of the top: exact, whatever the top's (stale) global pose.
  auto residual = [&](const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double* theta_q) {
    const double c1 = std::cos(p1.z());
    const double s1 = std::sin(p1.z());
    *theta_q = p1.z() + edge.z.z();
    return Eigen::Vector3d(p1.x() + c1 * edge.z.x() - s1 * edge.z.y() - p2.x(),
                           p1.y() + s1 * edge.z.x() + c1 * edge.z.y() - p2.y(),
                           NormalizeAngle(p1.z() + edge.z.z() - p2.z()));
  };
  double theta_q = 0.0;
  Eigen::Vector3d r =
      residual(ComposeBranch(branch1_, nullptr), ComposeBranch(branch2_, nullptr), &theta_q);

  // 1. Rotation: the heading correction, split along the path; each node's share rotates the
  //    subtree below it.
  {
    const double d = 2.0 * (RotateInformation(edge.information, theta_q) * r).z();
    double beta = length * d / (gamma_.z() * t_edge);
    if (std::abs(beta) > std::abs(r.z())) {
      beta = r.z();
    }
    if (total_share_.z() > 0.0) {
      std::size_t k = 0;
      for (int dir = 0; dir < 2; ++dir) {
        const double sign = dir == 0 ? -1.0 : 1.0;
        for (const int v : dir == 0 ? branch1_ : branch2_) {
          param_[U(v)].z() += sign * beta * share_[k++].z() / total_share_.z();
        }
      }
    }
  }
  // 2. Translation: the remaining position residual in the top's frame, split along the path;
  //    each share is expressed in its node's parent frame.
  const Eigen::Vector3d p1 = ComposeBranch(branch1_, &theta1_);
  const Eigen::Vector3d p2 = ComposeBranch(branch2_, &theta2_);
  r = residual(p1, p2, &theta_q);
  const Eigen::Vector3d d = 2.0 * (RotateInformation(edge.information, theta_q) * r);
  Eigen::Vector2d beta;
  for (int dim = 0; dim < 2; ++dim) {
    beta[dim] = length * d[dim] / (gamma_[dim] * t_edge);
    if (std::abs(beta[dim]) > std::abs(r[dim])) {
      beta[dim] = r[dim];
    }
  }
  std::size_t k = 0;
  for (int dir = 0; dir < 2; ++dir) {
    const double sign = dir == 0 ? -1.0 : 1.0;
    const auto& branch = dir == 0 ? branch1_ : branch2_;
    const auto& parent_theta = dir == 0 ? theta1_ : theta2_;
    for (std::size_t n = 0; n < branch.size(); ++n) {
      const Eigen::Vector3d& share = share_[k++];
      Eigen::Vector2d delta(0.0, 0.0);
      for (int dim = 0; dim < 2; ++dim) {
        if (total_share_[dim] > 0.0) {
          delta[dim] = sign * beta[dim] * share[dim] / total_share_[dim];
        }
      }
      const double c = std::cos(parent_theta[n]);
      const double s = std::sin(parent_theta[n]);
      param_[U(branch[n])].x() += c * delta.x() + s * delta.y();
      param_[U(branch[n])].y() += -s * delta.x() + c * delta.y();
    }
  }
}

}  // namespace gridslam::pose_graph
