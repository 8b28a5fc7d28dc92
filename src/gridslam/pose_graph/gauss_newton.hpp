// Sparse Gauss-Newton and Levenberg-Marquardt on the g2o error of edge_error.hpp: the reference
// solver that measures how close SGD gets to the optimum, and the final polish of `sgd+gn`
// (docs/design.md §1.7, docs/method.md §4.3). The normal equations H dx = -b are assembled block by
// block (3x3 per vertex pair, lower triangle) into a compressed sparse matrix whose pattern and
// AMD ordering are computed once; each iteration only refills the values and runs a numeric
// sparse Cholesky (Eigen's SimplicialLDLT). Fixed vertices (and one anchor per component, see
// graph_utils.hpp) are left out of the system. Gauss-Newton backtracks (halves the step) when a
// step would raise the cost, and stops if halving does not help, so the cost never increases;
// Levenberg-Marquardt damps with lambda * diag(H) (Marquardt) and Nielsen's update. Optional robust
// kernels (Huber, Cauchy) reweight each edge by rho'(e^T Omega e) (iteratively reweighted least
// squares, as g2o does), for loop closures that may be wrong.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

struct GaussNewtonOptions {
  /// Iteration limit of one Gauss-Newton or LM run.
  int max_iterations = 50;
  /// Stop when an accepted step lowers the cost by less than this fraction of it.
  double relative_tolerance = 1e-6;
  /// Robust kernel on each edge's chi^2: "none", "huber", "cauchy", "dcs" (dynamic covariance
  /// scaling, Phi = robust_width^2), "geman_mcclure" (scale robust_width^2) or "truncated"
  /// (min(chi^2, robust_width^2): edges above drop out).
  std::string robust_kernel = "none";
  /// Kernel width: residuals with sqrt(chi^2) above it are down-weighted [sqrt(chi^2)].
  double robust_width = 1.0;
  /// Edges the kernel applies to: "loops" (loop closures, IsLoopClosure in pose_graph.hpp; the
  /// odometry chain is trusted) or "all".
  std::string robust_edges = "loops";
  /// Levenberg-Marquardt: initial damping lambda of H + lambda diag(H) (small: on the shared
  /// graphs larger values only slow LM down from the odometry guess).
  double lm_initial_lambda = 1e-8;
  /// Gauss-Newton: step halvings tried before giving up when the cost would rise.
  int max_step_halvings = 8;

  template <class V>
  void Visit(V& v) {
    v("max_iterations", max_iterations, "Iteration limit of a Gauss-Newton/LM run");
    v("relative_tolerance", relative_tolerance,
      "Stop when a step lowers the cost by less than this fraction");
    v("robust_kernel", robust_kernel,
      "Robust kernel on edge chi^2: none, huber, cauchy, dcs, geman_mcclure or truncated");
    v("robust_width", robust_width, "Robust kernel width [sqrt(chi^2)]");
    v("robust_edges", robust_edges, "Edges the kernel applies to: loops or all");
    v("lm_initial_lambda", lm_initial_lambda, "LM initial damping of H + lambda diag(H)");
    v("max_step_halvings", max_step_halvings, "Gauss-Newton backtracking steps");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(max_iterations >= 0, "optimizer.gn.max_iterations >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(relative_tolerance >= 0.0, "optimizer.gn.relative_tolerance >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(robust_kernel == "none" || robust_kernel == "huber" || robust_kernel == "cauchy" ||
                    robust_kernel == "dcs" || robust_kernel == "geman_mcclure" ||
                    robust_kernel == "truncated",
                "optimizer.gn.robust_kernel is none, huber, cauchy, dcs, geman_mcclure or "
                "truncated"));
    GRIDSLAM_RETURN_IF_ERROR(Require(robust_edges == "loops" || robust_edges == "all",
                                     "optimizer.gn.robust_edges is loops or all"));
    GRIDSLAM_RETURN_IF_ERROR(Require(robust_width > 0.0, "optimizer.gn.robust_width > 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(lm_initial_lambda > 0.0, "optimizer.gn.lm_initial_lambda > 0"));
    return Require(max_step_halvings >= 0, "optimizer.gn.max_step_halvings >= 0");
  }
};

/// One iteration of a least-squares run, for reports and --verbose.
struct LeastSquaresIteration {
  int iteration = 0;
  double chi2 = 0.0;    ///< Plain g2o chi^2 after the iteration.
  double cost = 0.0;    ///< Robust cost (equals chi2 without a kernel).
  double lambda = 0.0;  ///< LM damping used (0 for Gauss-Newton).
  bool accepted = true;
};

struct LeastSquaresSummary {
  double chi2_initial = 0.0;
  double chi2_final = 0.0;
  int iterations = 0;              ///< Linear solves that changed the estimate or were tried.
  bool converged = false;          ///< The relative tolerance was met (not the iteration limit).
  bool numerical_failure = false;  ///< The factorization failed.
};

namespace internal {
class NormalEquations;
}  // namespace internal

/// A Gauss-Newton/LM solver bound to one graph's structure (vertices and edges may not be added
/// while it lives; poses may change). Not thread-safe.
class GaussNewtonSolver {
 public:
  /// `fixed`: per vertex index, held constant (use EffectiveFixed(graph)).
  GaussNewtonSolver(const PoseGraph& graph, const std::vector<bool>& fixed,
                    GaussNewtonOptions options);
  ~GaussNewtonSolver();
  GaussNewtonSolver(const GaussNewtonSolver&) = delete;
  GaussNewtonSolver& operator=(const GaussNewtonSolver&) = delete;

  using Callback = std::function<void(const LeastSquaresIteration&)>;
  /// Runs Gauss-Newton (levenberg = false) or LM on `graph`'s poses, in place, for up to
  /// `max_iterations` (<= 0: the options' limit). `graph` must be the graph given to the
  /// constructor or have the same structure.
  LeastSquaresSummary Run(PoseGraph& graph, bool levenberg, int max_iterations = 0,
                          const Callback& callback = {});

  /// Changes the kernel and its width between runs (graduated non-convexity, the truncated
  /// polish); the edges it applies to stay as constructed. Checked like the options.
  void SetRobustKernel(const std::string& kernel, double width);

 private:
  GaussNewtonOptions options_;
  std::unique_ptr<internal::NormalEquations> system_;
};

}  // namespace gridslam::pose_graph
