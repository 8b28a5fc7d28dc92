#include "gridslam/pose_graph/optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "gridslam/common/check.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/initialization.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"

namespace gridslam::pose_graph {

namespace {

/// Sum over edges of chi^2, with robust edges capped at `cap` (no cap when 0).
double TruncatedCost(const PoseGraph& graph, double cap, const std::string& robust_edges) {
  double cost = 0.0;
  for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
    const double chi2 = EdgeChi2(graph, k);
    const bool robust = robust_edges == "all" || IsLoopClosure(graph.edge(k));
    cost += robust && cap > 0.0 ? std::min(chi2, cap) : chi2;
  }
  return cost;
}

}  // namespace

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
  Initialization initialization = Initialization::kNone;
  ParseInitialization(options.initialization, &initialization);
  if (initialization != Initialization::kNone) {
    report.initialized = InitializeOrientationFirst(graph, initialization);
  }
  // SGD has no outlier defence (a few wrong closures bend its result beyond what Gauss-Newton can
  // undo), so with a robust mechanism sgd+gn runs the robust least-squares stage alone; after an
  // orientation-first initialization SGD's warm-up is not needed either (and, measured on noisy
  // M3500, its large first steps move the guess out of the global basin).
  const bool use_sgd = options.method == "sgd" ||
                       (options.method == "sgd+gn" && options.robust.mechanism == "none" &&
                        initialization == Initialization::kNone);
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
    const RobustOptions& robust = options.robust;
    GaussNewtonOptions gn = options.gn;
    int ls_iteration = 0;
    GaussNewtonSolver solver(graph, EffectiveFixed(graph), gn);
    auto run = [&](const std::string& name, int limit) {
      GaussNewtonSolver::Callback ls_callback;
      if (callback) {
        ls_callback = [&](const LeastSquaresIteration& it) {
          callback(IterationRecord{name, ls_iteration + it.iteration, it.chi2, elapsed()});
        };
      }
      const LeastSquaresSummary summary = solver.Run(graph, levenberg, limit, ls_callback);
      ls_iteration += summary.iterations;
      report.converged = summary.converged;
    };
    if (robust.mechanism == "gnc") {
      // Yang et al. 2020: mu starts at 2 max r^2 / c^2 (the cost is then convex in the residuals
      // that matter) and is divided by gnc_factor per step down to 1.
      double max_chi2 = 0.0;
      for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
        if (IsLoopClosure(graph.edge(k))) {
          max_chi2 = std::max(max_chi2, EdgeChi2(graph, k));
        }
      }
      double mu = std::max(1.0, 2.0 * max_chi2 / robust.gnc_threshold);
      while (true) {
        solver.SetRobustKernel("geman_mcclure", std::sqrt(mu * robust.gnc_threshold));
        run("gnc", mu > 1.0 ? robust.gnc_step_iterations : iterations);
        if (mu <= 1.0) {
          break;
        }
        mu = std::max(1.0, mu / robust.gnc_factor);
      }
    } else if (robust.mechanism == "dcs") {
      // One run per Phi from the same start, each polished by the truncated cost; the result with
      // the lowest truncated cost wins (a small Phi keeps wrong closures out from a good start, a
      // large one keeps correct closures in despite a drifted start).
      std::vector<Pose2> initial(graph.num_vertices());
      for (int v = 0; v < static_cast<int>(initial.size()); ++v) {
        initial[static_cast<std::size_t>(v)] = graph.vertex(v).T_map_v;
      }
      std::vector<Pose2> best;
      double best_cost = 0.0;
      for (const double phi : robust.dcs_phi) {
        for (int v = 0; v < static_cast<int>(initial.size()); ++v) {
          graph.SetPose(v, initial[static_cast<std::size_t>(v)]);
        }
        solver.SetRobustKernel("dcs", std::sqrt(phi));
        run("dcs", iterations);
        if (robust.inlier_chi2 > 0.0) {
          solver.SetRobustKernel("truncated", std::sqrt(robust.inlier_chi2));
          run(stage, iterations);
        }
        const double cost = TruncatedCost(graph, robust.inlier_chi2, options.gn.robust_edges);
        if (best.empty() || cost < best_cost) {
          best_cost = cost;
          best.resize(initial.size());
          for (int v = 0; v < static_cast<int>(initial.size()); ++v) {
            best[static_cast<std::size_t>(v)] = graph.vertex(v).T_map_v;
          }
        }
      }
      for (int v = 0; v < static_cast<int>(best.size()); ++v) {
        graph.SetPose(v, best[static_cast<std::size_t>(v)]);
      }
    } else {
      run(stage, iterations);
    }
    if (robust.mechanism == "gnc" && robust.inlier_chi2 > 0.0) {
      solver.SetRobustKernel("truncated", std::sqrt(robust.inlier_chi2));
      run(stage, iterations);
    }
    report.ls_iterations = ls_iteration;
  }
  report.iterations = report.sgd_iterations + report.ls_iterations;
  report.chi2_final = Chi2(graph);
  report.chi2_inliers = report.chi2_final;
  if (options.robust.mechanism != "none") {
    report.chi2_inliers = 0.0;
    for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
      const double chi2 = EdgeChi2(graph, k);
      const bool robust_edge = options.gn.robust_edges == "all" || IsLoopClosure(graph.edge(k));
      if (robust_edge && options.robust.inlier_chi2 > 0.0 && chi2 > options.robust.inlier_chi2) {
        ++report.rejected_edges;
      } else {
        report.chi2_inliers += chi2;
      }
    }
  }
  report.seconds = elapsed();
  report.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return report;
}

}  // namespace gridslam::pose_graph
