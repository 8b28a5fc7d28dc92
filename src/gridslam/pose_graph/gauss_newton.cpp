#include "gridslam/pose_graph/gauss_newton.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gridslam/common/check.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/internal/block_cholesky.hpp"

namespace gridslam::pose_graph {

namespace internal {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

/// Robust kernel rho(s) of the squared error s = e^T Omega e and its derivative (g2o's
/// RobustKernelHuber / RobustKernelCauchy with delta = width; dynamic covariance scaling, Agarwal
/// et al. 2013, with Phi = width^2; Geman-McClure with scale width^2, the kernel of GNC; truncated
/// least squares at width^2, the polish after them).
struct Kernel {
  int kind = 0;  // 0 none, 1 Huber, 2 Cauchy, 3 DCS, 4 Geman-McClure, 5 truncated.
  double delta2 = 1.0;

  void Evaluate(double s, double* rho, double* weight) const {
    if (kind == 1 && s > delta2) {
      const double root = std::sqrt(s);
      const double delta = std::sqrt(delta2);
      *rho = 2.0 * delta * root - delta2;
      *weight = delta / root;
    } else if (kind == 2) {
      *rho = delta2 * std::log1p(s / delta2);
      *weight = 1.0 / (1.0 + s / delta2);
    } else if (kind == 3 && s > delta2) {
      // DCS scales the information by w = (2 Phi / (Phi + s))^2 (the square of the closed-form
      // switch of switchable constraints); rho' = w and continuity at s = Phi give this rho.
      const double q = delta2 + s;
      *rho = delta2 * (3.0 * s - delta2) / q;
      *weight = 4.0 * delta2 * delta2 / (q * q);
    } else if (kind == 5) {
      *rho = std::min(s, delta2);  // Truncated least squares: edges above delta2 drop out.
      *weight = s <= delta2 ? 1.0 : 0.0;
    } else if (kind == 4) {
      const double q = delta2 + s;
      *rho = delta2 * s / q;
      *weight = delta2 * delta2 / (q * q);
    } else {
      *rho = s;
      *weight = 1.0;
    }
  }
};

int KernelKind(const std::string& name) {
  if (name == "huber") {
    return 1;
  }
  if (name == "cauchy") {
    return 2;
  }
  if (name == "dcs") {
    return 3;
  }
  if (name == "geman_mcclure") {
    return 4;
  }
  if (name == "truncated") {
    return 5;
  }
  return 0;
}

}  // namespace

class NormalEquations {
 public:
  /// `robust_all`: the kernel applies to every edge, else only to loop closures (IsLoopClosure).
  NormalEquations(const PoseGraph& graph, const std::vector<bool>& fixed, bool robust_all);

  /// Cost (robust) and plain chi^2 at poses x.
  void Evaluate(const std::vector<Eigen::Vector3d>& x, const Kernel& kernel, double* cost,
                double* chi2) const;
  /// Fills H and b at poses x.
  void Linearize(const std::vector<Eigen::Vector3d>& x, const Kernel& kernel);
  /// Factorizes H + lambda diag(H) (Marquardt's scaling); false on a numerical failure.
  bool Factorize(double lambda) { return cholesky_.Factorize(lambda, /*scaled=*/true); }
  /// dx = -(H + lambda diag(H))^-1 b for the last factorization.
  [[nodiscard]] Eigen::VectorXd Solve() const { return cholesky_.Solve(-b_); }
  [[nodiscard]] double MaxDiagonal() const { return cholesky_.MaxDiagonal(); }
  [[nodiscard]] const Eigen::VectorXd& gradient() const { return b_; }
  /// x_new = x + step * dx on the free vertices.
  void Apply(const std::vector<Eigen::Vector3d>& x, const Eigen::VectorXd& dx, double step,
             std::vector<Eigen::Vector3d>& x_new) const;
  /// dx^T H dx (H without damping).
  [[nodiscard]] double Quadratic(const Eigen::VectorXd& dx) const {
    return cholesky_.Quadratic(dx);
  }

 private:
  struct EdgeSlots {
    int i = 0;  ///< Vertex indices.
    int j = 0;
    int bi = -1;  ///< Variable blocks (-1: fixed).
    int bj = -1;
    BlockCholesky::Slot ii;
    BlockCholesky::Slot jj;
    BlockCholesky::Slot ij;  ///< Block (bi, bj) of H.
    Eigen::Vector3d z;
    double cos_z = 1.0;
    double sin_z = 0.0;
    Eigen::Matrix3d information;
    bool robust = true;  ///< The kernel applies.
  };

  static BlockCholesky Build(const PoseGraph& graph, const std::vector<int>& block, int num_blocks);

  int num_blocks_ = 0;      // Declared before block_, which sets it.
  std::vector<int> block_;  ///< Per vertex index: variable block or -1.
  std::vector<EdgeSlots> edges_;
  BlockCholesky cholesky_;
  Eigen::VectorXd b_;
};

namespace {

std::vector<int> NumberFreeVertices(const PoseGraph& graph, const std::vector<bool>& fixed,
                                    int* count) {
  GRIDSLAM_CHECK(fixed.size() == graph.num_vertices()) << "fixed flags must cover every vertex";
  std::vector<int> block(fixed.size(), -1);
  int blocks = 0;
  for (std::size_t v = 0; v < fixed.size(); ++v) {
    if (!fixed[v]) {
      block[v] = blocks++;
    }
  }
  *count = blocks;
  return block;
}

}  // namespace

BlockCholesky NormalEquations::Build(const PoseGraph& graph, const std::vector<int>& block,
                                     int num_blocks) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(graph.num_edges());
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    const int bi = block[U(graph.FromIndex(k))];
    const int bj = block[U(graph.ToIndex(k))];
    if (bi >= 0 && bj >= 0 && bi != bj) {
      pairs.emplace_back(bi, bj);
    }
  }
  return BlockCholesky(num_blocks, pairs);
}

NormalEquations::NormalEquations(const PoseGraph& graph, const std::vector<bool>& fixed,
                                 bool robust_all)
    : block_(NumberFreeVertices(graph, fixed, &num_blocks_)),
      cholesky_(Build(graph, block_, num_blocks_)),
      b_(Eigen::VectorXd::Zero(3 * num_blocks_)) {
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    EdgeSlots s;
    s.i = graph.FromIndex(k);
    s.j = graph.ToIndex(k);
    s.bi = block_[U(s.i)];
    s.bj = block_[U(s.j)];
    s.z = graph.edge(k).T_i_j.ToVector();
    s.cos_z = std::cos(s.z.z());
    s.sin_z = std::sin(s.z.z());
    s.information = graph.edge(k).information;
    s.robust = robust_all || IsLoopClosure(graph.edge(k));
    if (s.bi >= 0) {
      s.ii = cholesky_.Find(s.bi, s.bi);
    }
    if (s.bj >= 0) {
      s.jj = cholesky_.Find(s.bj, s.bj);
    }
    if (s.bi >= 0 && s.bj >= 0) {
      s.ij = cholesky_.Find(s.bi, s.bj);
    }
    edges_.push_back(s);
  }
}

void NormalEquations::Evaluate(const std::vector<Eigen::Vector3d>& x, const Kernel& kernel,
                               double* cost, double* chi2) const {
  double total_cost = 0.0;
  double total_chi2 = 0.0;
  for (const EdgeSlots& s : edges_) {
    const Eigen::Vector3d e = EdgeError(x[U(s.i)], x[U(s.j)], s.z, s.cos_z, s.sin_z);
    const double s2 = e.dot(s.information * e);
    double rho = s2;
    double weight = 1.0;
    if (kernel.kind != 0 && s.robust) {
      kernel.Evaluate(s2, &rho, &weight);
    }
    total_cost += rho;
    total_chi2 += s2;
  }
  *cost = total_cost;
  *chi2 = total_chi2;
}

void NormalEquations::Linearize(const std::vector<Eigen::Vector3d>& x, const Kernel& kernel) {
  cholesky_.SetZero();
  std::vector<Eigen::Matrix3d>& values = cholesky_.values();
  b_.setZero();
  Eigen::Matrix3d J_i;
  Eigen::Matrix3d J_j;
  for (const EdgeSlots& s : edges_) {
    if (s.bi < 0 && s.bj < 0) {
      continue;
    }
    const Eigen::Vector3d e = EdgeError(x[U(s.i)], x[U(s.j)], s.z, s.cos_z, s.sin_z, &J_i, &J_j);
    double weight = 1.0;
    if (kernel.kind != 0 && s.robust) {
      double rho = 0.0;
      kernel.Evaluate(e.dot(s.information * e), &rho, &weight);
    }
    const Eigen::Matrix3d omega = weight * s.information;
    const Eigen::Matrix3d A = J_i.transpose() * omega;
    const Eigen::Matrix3d B = J_j.transpose() * omega;
    if (s.bi >= 0) {
      values[U(s.ii.index)].noalias() += A * J_i;
      b_.segment<3>(3 * s.bi).noalias() += A * e;
    }
    if (s.bj >= 0) {
      values[U(s.jj.index)].noalias() += B * J_j;
      b_.segment<3>(3 * s.bj).noalias() += B * e;
    }
    if (s.bi >= 0 && s.bj >= 0) {
      if (s.ij.transposed) {
        values[U(s.ij.index)].noalias() += B * J_i;  // H_ji = H_ij^T.
      } else {
        values[U(s.ij.index)].noalias() += A * J_j;
      }
    }
  }
}

void NormalEquations::Apply(const std::vector<Eigen::Vector3d>& x, const Eigen::VectorXd& dx,
                            double step, std::vector<Eigen::Vector3d>& x_new) const {
  x_new = x;
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (block_[v] >= 0) {
      x_new[v] += step * dx.segment<3>(3 * block_[v]);
    }
  }
}

}  // namespace internal

GaussNewtonSolver::GaussNewtonSolver(const PoseGraph& graph, const std::vector<bool>& fixed,
                                     GaussNewtonOptions options)
    : options_(std::move(options)),
      system_(std::make_unique<internal::NormalEquations>(graph, fixed,
                                                          options_.robust_edges == "all")) {
  GRIDSLAM_CHECK(options_.Validate().ok()) << options_.Validate().error().ToString();
}

GaussNewtonSolver::~GaussNewtonSolver() = default;

void GaussNewtonSolver::SetRobustKernel(const std::string& kernel, double width) {
  options_.robust_kernel = kernel;
  options_.robust_width = width;
  GRIDSLAM_CHECK(options_.Validate().ok()) << options_.Validate().error().ToString();
}

LeastSquaresSummary GaussNewtonSolver::Run(PoseGraph& graph, bool levenberg, int max_iterations,
                                           const Callback& callback) {
  internal::Kernel kernel;
  kernel.kind = internal::KernelKind(options_.robust_kernel);
  kernel.delta2 = options_.robust_width * options_.robust_width;
  const int limit = max_iterations > 0 ? max_iterations : options_.max_iterations;

  std::vector<Eigen::Vector3d> x(graph.num_vertices());
  for (std::size_t v = 0; v < x.size(); ++v) {
    x[v] = graph.vertex(static_cast<int>(v)).T_map_v.ToVector();
  }
  std::vector<Eigen::Vector3d> x_new;
  double cost = 0.0;
  double chi2 = 0.0;
  system_->Evaluate(x, kernel, &cost, &chi2);
  LeastSquaresSummary summary;
  summary.chi2_initial = chi2;

  double lambda = 0.0;
  double nu = 2.0;
  bool linearized = false;
  while (summary.iterations < limit && cost > 0.0) {
    if (!linearized) {
      system_->Linearize(x, kernel);
      linearized = true;
      if (levenberg && lambda == 0.0) {
        lambda = options_.lm_initial_lambda;
      }
    }
    ++summary.iterations;
    if (!system_->Factorize(levenberg ? lambda : 0.0)) {
      if (levenberg) {
        lambda *= nu;
        nu *= 2.0;
        continue;
      }
      summary.numerical_failure = true;
      break;
    }
    const Eigen::VectorXd dx = system_->Solve();
    double new_cost = 0.0;
    double new_chi2 = 0.0;
    bool accepted = false;
    if (levenberg) {
      system_->Apply(x, dx, 1.0, x_new);
      system_->Evaluate(x_new, kernel, &new_cost, &new_chi2);
      // Gain ratio of the actual to the predicted decrease of the cost (Madsen-Nielsen).
      const double predicted = -2.0 * dx.dot(system_->gradient()) - system_->Quadratic(dx);
      const double rho = predicted > 0.0 ? (cost - new_cost) / predicted : -1.0;
      if (rho > 0.0 && new_cost <= cost) {
        accepted = true;
        lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
        nu = 2.0;
      } else {
        lambda *= nu;
        nu *= 2.0;
      }
    } else {
      double step = 1.0;
      for (int h = 0; h <= options_.max_step_halvings; ++h, step *= 0.5) {
        system_->Apply(x, dx, step, x_new);
        system_->Evaluate(x_new, kernel, &new_cost, &new_chi2);
        if (new_cost <= cost) {
          accepted = true;
          break;
        }
      }
    }
    if (callback) {
      callback(LeastSquaresIteration{summary.iterations, accepted ? new_chi2 : chi2,
                                     accepted ? new_cost : cost, levenberg ? lambda : 0.0,
                                     accepted});
    }
    if (!accepted) {
      if (levenberg && lambda < 1e32) {
        continue;
      }
      summary.converged = true;  // No step lowers the cost: a (local) minimum.
      break;
    }
    const double decrease = (cost - new_cost) / std::max(cost, 1e-300);
    std::swap(x, x_new);
    cost = new_cost;
    chi2 = new_chi2;
    linearized = false;
    if (decrease < options_.relative_tolerance) {
      summary.converged = true;
      break;
    }
  }
  for (std::size_t v = 0; v < x.size(); ++v) {
    graph.SetPose(static_cast<int>(v), Pose2::FromVector(x[v]));
  }
  summary.chi2_final = chi2;
  return summary;
}

}  // namespace gridslam::pose_graph
