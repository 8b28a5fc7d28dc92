// One entry point for the back end (docs/design.md §1.7, §3.3): Optimize(graph, options) runs SGD
// (sgd_optimizer.hpp), sparse Gauss-Newton or Levenberg-Marquardt (gauss_newton.hpp), or SGD to
// get into the basin of the optimum followed by Gauss-Newton to converge ("sgd+gn", the default),
// on a graph in place, and returns an OptimizationReport with chi^2 before/after, iteration
// counts and the optimization time. Every component is anchored first (graph_utils.hpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gridslam/common/options.hpp"
#include "gridslam/pose_graph/gauss_newton.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"
#include "gridslam/pose_graph/robust_options.hpp"
#include "gridslam/pose_graph/sgd_options.hpp"

namespace gridslam::pose_graph {

struct OptimizerOptions {
  /// "sgd", "gn" (Gauss-Newton), "lm" (Levenberg-Marquardt) or "sgd+gn".
  std::string method = "sgd+gn";
  /// SGD iterations of method "sgd".
  int sgd_iterations = 100;
  /// SGD iterations before the Gauss-Newton polish of "sgd+gn". Two suffice on the shared graphs
  /// (one already gets MIT out of the local minimum where Gauss-Newton alone stops at 770.7).
  int warmup_iterations = 2;
  /// Initial guess computed first (initialization.hpp): "none" (the graph's poses), "chordal"
  /// (chordal relaxation of the orientations, then positions) or "lago" (LAGO's regularized
  /// linear orientations, then positions). With a robust mechanism, the robust stage runs from
  /// three starts (the graph's poses, the initialization from all edges, and from the edges the
  /// first run kept) and keeps the lowest truncated cost. sgd+gn skips SGD when this is set.
  std::string initialization = "none";
  SgdOptions sgd;
  GaussNewtonOptions gn;
  /// Defence against wrong loop closures (robust_options.hpp); applies to the least-squares
  /// stage (gn, lm, the polish of sgd+gn).
  RobustOptions robust;

  template <class V>
  void Visit(V& v) {
    v("method", method, "Optimizer: sgd, gn, lm or sgd+gn (SGD, then Gauss-Newton)");
    v("sgd_iterations", sgd_iterations, "Iterations of SGD alone (method sgd)");
    v("warmup_iterations", warmup_iterations, "SGD iterations before Gauss-Newton in sgd+gn");
    v("initialization", initialization,
      "Initial guess: none (graph poses), chordal or lago (orientations first, then positions)");
    v.Section("sgd", sgd, "Tree-parameterized SGD (Olson 2006, TORO 2007, Grisetti 2009)");
    v.Section("gn", gn, "Sparse Gauss-Newton / Levenberg-Marquardt");
    v.Section("robust", robust, "Defence against wrong loop closures (DCS or GNC on loop edges)");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(method == "sgd" || method == "gn" || method == "lm" || method == "sgd+gn",
                "optimizer.method is sgd, gn, lm or sgd+gn"));
    GRIDSLAM_RETURN_IF_ERROR(Require(sgd_iterations >= 0, "optimizer.sgd_iterations >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(warmup_iterations >= 0, "optimizer.warmup_iterations >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(initialization == "none" || initialization == "chordal" || initialization == "lago",
                "optimizer.initialization is none, chordal or lago"));
    GRIDSLAM_RETURN_IF_ERROR(sgd.Validate());
    GRIDSLAM_RETURN_IF_ERROR(robust.Validate());
    return gn.Validate();
  }
};

/// One iteration of any stage, for --verbose and reports.
struct IterationRecord {
  std::string stage;     ///< "sgd", "gn" or "lm".
  int iteration = 0;     ///< 1-based within the stage.
  double chi2 = 0.0;     ///< g2o chi^2 after the iteration.
  double seconds = 0.0;  ///< Time since the start of Optimize().
};

struct OptimizationReport {
  std::string method;
  double chi2_initial = 0.0;
  double chi2_final = 0.0;
  int iterations = 0;  ///< All iterations (SGD + least squares).
  int sgd_iterations = 0;
  int ls_iterations = 0;     ///< Gauss-Newton / LM iterations.
  bool converged = false;    ///< The least-squares stage met its tolerance (false for sgd).
  double seconds = 0.0;      ///< Optimization wall time (no file I/O).
  double cpu_seconds = 0.0;  ///< Processor time of the process meanwhile (robust to a busy host).
  int components = 0;        ///< Connected components (each anchored once).
  bool initialized = false;  ///< The orientation-first initialization ran and succeeded.
  /// Robust mechanism: loop edges whose final chi^2 exceeds robust.inlier_chi2 (taken as wrong).
  int rejected_edges = 0;
  /// chi^2 of the edges not rejected (equals chi2_final without a robust mechanism).
  double chi2_inliers = 0.0;
};

using IterationCallback = std::function<void(const IterationRecord&)>;

/// Optimizes `graph`'s poses in place. `iterations` > 0 overrides the iteration count of the
/// method (SGD iterations for sgd, least-squares iterations for gn/lm/the polish of sgd+gn).
/// With a callback, chi^2 is computed and reported after every iteration (costs time).
/// Options must be valid (checked).
OptimizationReport Optimize(PoseGraph& graph, const OptimizerOptions& options, int iterations = 0,
                            const IterationCallback& callback = {});

}  // namespace gridslam::pose_graph
