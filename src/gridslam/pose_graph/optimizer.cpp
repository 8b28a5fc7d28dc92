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
  const bool robust_on = options.robust.mechanism != "none";
  // With a robust mechanism the initialization runs inside the robust stage, on the edges that
  // stage kept (a least-squares initialization from all edges would be bent by wrong ones).
  if (initialization != Initialization::kNone && !robust_on) {
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
    auto poses = [&] {
      std::vector<Pose2> out(graph.num_vertices());
      for (int v = 0; v < static_cast<int>(out.size()); ++v) {
        out[static_cast<std::size_t>(v)] = graph.vertex(v).T_map_v;
      }
      return out;
    };
    auto set_poses = [&](const std::vector<Pose2>& in) {
      for (int v = 0; v < static_cast<int>(in.size()); ++v) {
        graph.SetPose(v, in[static_cast<std::size_t>(v)]);
      }
    };
    auto polish = [&] {
      if (robust.inlier_chi2 > 0.0) {
        solver.SetRobustKernel("truncated", std::sqrt(robust.inlier_chi2));
        run(stage, iterations);
      }
      return TruncatedCost(graph, robust.inlier_chi2, options.gn.robust_edges);
    };
    // One robust pass from the graph's current poses; leaves its result in the graph and returns
    // its truncated cost.
    auto robust_pass = [&]() -> double {
      if (robust.mechanism == "gnc") {
        // Yang et al. 2020: mu starts at 2 max r^2 / c^2 (the cost is then convex in the
        // residuals that matter) and is divided by gnc_factor per step down to 1.
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
        return polish();
      }
      // DCS: one run per Phi from the same start, each polished; the lowest truncated cost wins
      // (a small Phi keeps wrong closures out from a good start, a large one keeps correct
      // closures in despite a drifted start).
      const std::vector<Pose2> initial = poses();
      std::vector<Pose2> best;
      double best_cost = 0.0;
      for (const double phi : robust.dcs_phi) {
        set_poses(initial);
        solver.SetRobustKernel("dcs", std::sqrt(phi));
        run("dcs", iterations);
        const double cost = polish();
        if (best.empty() || cost < best_cost) {
          best_cost = cost;
          best = poses();
        }
      }
      set_poses(best);
      return best_cost;
    };
    if (!robust_on) {
      run(stage, iterations);
    } else {
      std::vector<Pose2> best;
      double best_cost = 0.0;
      auto pass_from = [&](const std::vector<Pose2>& start_poses) {
        set_poses(start_poses);
        const double cost = robust_pass();
        if (best.empty() || cost < best_cost) {
          best_cost = cost;
          best = poses();
        }
      };
      const std::vector<Pose2> given = poses();
      pass_from(given);
      if (initialization != Initialization::kNone) {
        // Two more starts, the better truncated cost wins: the initialization from all edges
        // (right when there are no wrong ones; MIT needs it) and from the edges the first pass
        // kept (right when there are).
        PoseGraph kept;
        for (const Vertex& v : graph.vertices()) {
          kept.AddVertex(v.id, v.T_map_v, v.fixed);
        }
        for (int k = 0; k < static_cast<int>(graph.num_edges()); ++k) {
          const Edge& e = graph.edge(k);
          const bool robust_edge = options.gn.robust_edges == "all" || IsLoopClosure(e);
          if (!robust_edge || robust.inlier_chi2 <= 0.0 ||
              EdgeChi2(graph, k) <= robust.inlier_chi2) {
            kept.AddEdge(e.from, e.to, e.T_i_j, e.information, e.role);
          }
        }
        for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
          kept.SetPose(v, given[static_cast<std::size_t>(v)]);
        }
        set_poses(given);
        if (InitializeOrientationFirst(graph, initialization)) {
          report.initialized = true;
          pass_from(poses());
        }
        if (InitializeOrientationFirst(kept, initialization)) {
          report.initialized = true;
          std::vector<Pose2> start_poses;
          for (const Vertex& v : kept.vertices()) {
            start_poses.push_back(v.T_map_v);
          }
          pass_from(start_poses);
        }
      }
      set_poses(best);
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
