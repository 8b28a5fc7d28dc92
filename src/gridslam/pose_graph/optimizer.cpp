#include "gridslam/pose_graph/optimizer.hpp"

#include <chrono>
#include <ctime>

#include "gridslam/common/check.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"

namespace gridslam::pose_graph {

OptimizationReport Optimize(PoseGraph& graph, const OptimizerOptions& options, int iterations,
                            const IterationCallback& callback) {
  GRIDSLAM_CHECK(options.Validate().ok()) << options.Validate().error().ToString();
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  OptimizationReport report;
  report.method = options.method;
  report.chi2_initial = Chi2(graph);
  report.components = ConnectedComponents(graph).count;
  const bool use_sgd = options.method == "sgd" || options.method == "sgd+gn";
  const bool use_ls = options.method != "sgd";

  if (use_sgd) {
    const int n = options.method == "sgd" ? (iterations > 0 ? iterations : options.sgd_iterations)
                                          : options.warmup_iterations;
    SgdOptimizer sgd(graph, options.sgd);
    for (int it = 1; it <= n; ++it) {
      sgd.Iterate(1);
      if (callback) {
        callback(IterationRecord{"sgd", it, sgd.Chi2(), elapsed()});
      }
    }
    report.sgd_iterations = n;
    const PoseGraph& result = sgd.graph();
    for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
      graph.SetPose(v, result.vertex(v).T_map_v);
    }
  }
  if (use_ls) {
    const bool levenberg = options.method == "lm";
    const std::string stage = levenberg ? "lm" : "gn";
    GaussNewtonSolver solver(graph, EffectiveFixed(graph), options.gn);
    GaussNewtonSolver::Callback ls_callback;
    if (callback) {
      ls_callback = [&](const LeastSquaresIteration& it) {
        callback(IterationRecord{stage, it.iteration, it.chi2, elapsed()});
      };
    }
    const LeastSquaresSummary summary = solver.Run(graph, levenberg, iterations, ls_callback);
    report.ls_iterations = summary.iterations;
    report.converged = summary.converged;
  }
  report.iterations = report.sgd_iterations + report.ls_iterations;
  report.chi2_final = Chi2(graph);
  report.seconds = elapsed();
  report.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return report;
}

}  // namespace gridslam::pose_graph
