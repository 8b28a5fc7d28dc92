// `gridslam optimize GRAPH -o OUT [--method sgd|gn|lm|sgd+gn] [--iterations N] [--json]
// [--verbose]`: optimizes a g2o or TORO 2-D pose graph (docs/design.md §2, §3.3) and writes it in
// the format of OUT's extension (.g2o or .graph). Prints chi^2 (g2o convention) before, after each
// iteration with --verbose, and at the end, with the iteration count and the optimization time
// (file I/O excluded); --json prints the same as one object. Bad input exits 2 with file:line and
// writes nothing. For the outlier benchmark (docs/robust_optimization.md), `--add-outliers N
// --outlier-kind random|local|group --seed S` adds wrong loop closures before optimizing and
// `--reference REF` reports the mean position error against REF's poses (same vertices).
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gridslam/io/g2o_io.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/pose_graph/outliers.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct OptimizeArgs {
  std::string graph;
  std::string output;
  bool json = false;
  bool verbose = false;
  int iterations = 0;
  std::string init = "auto";
  // Flags override the configuration; applied after --config was read.
  std::optional<std::string> method;
  std::optional<int> warmup;
  std::optional<std::string> sgd_tree;
  std::optional<std::string> sgd_variant;
  std::optional<std::string> robust_kernel;
  std::optional<double> robust_width;
  std::optional<std::string> robust_edges;
  std::optional<std::string> robust;
  std::optional<std::string> initialization;
  int add_outliers = 0;
  std::string outlier_kind = "random";
  unsigned seed = 1;
  std::string reference;
};

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int RunOptimize(const OptimizeArgs& args, AppContext& context) {
  pose_graph::OptimizerOptions& options = context.options.optimizer;
  options.method = args.method.value_or(options.method);
  options.warmup_iterations = args.warmup.value_or(options.warmup_iterations);
  options.sgd.tree = args.sgd_tree.value_or(options.sgd.tree);
  options.sgd.variant = args.sgd_variant.value_or(options.sgd.variant);
  options.gn.robust_kernel = args.robust_kernel.value_or(options.gn.robust_kernel);
  options.gn.robust_width = args.robust_width.value_or(options.gn.robust_width);
  options.gn.robust_edges = args.robust_edges.value_or(options.gn.robust_edges);
  options.robust.mechanism = args.robust.value_or(options.robust.mechanism);
  options.initialization = args.initialization.value_or(options.initialization);
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  if (!EndsWith(args.output, ".g2o") && !EndsWith(args.output, ".graph")) {
    return ReportError(InvalidInput("output must end in .g2o or .graph", args.output));
  }
  io::GraphReadStats stats;
  auto read = io::ReadPoseGraphFile(args.graph, &stats);
  if (!read.ok()) {
    return ReportError(read.error());
  }
  pose_graph::PoseGraph& graph = read.value();
  if (graph.num_edges() == 0) {
    return ReportError(InvalidInput("graph has no edges", args.graph));
  }
  // Vertices without an estimate (edges-only files) force the odometry-chained guess.
  const bool chain = args.init == "odometry" || (args.init == "auto" && stats.created_vertices > 0);
  if (chain) {
    pose_graph::InitializeByChaining(graph);
  }
  std::optional<pose_graph::PoseGraph> reference;
  if (!args.reference.empty()) {
    auto ref = io::ReadPoseGraphFile(args.reference);
    if (!ref.ok()) {
      return ReportError(ref.error());
    }
    bool same = ref.value().num_vertices() == graph.num_vertices();
    for (int v = 0; same && v < static_cast<int>(graph.num_vertices()); ++v) {
      same = ref.value().vertex(v).id == graph.vertex(v).id;
    }
    if (!same) {
      return ReportError(
          InvalidInput("reference graph has other vertices than GRAPH", args.reference));
    }
    reference = std::move(ref.value());
  }
  if (args.add_outliers > 0) {
    pose_graph::OutlierOptions outliers;
    outliers.count = args.add_outliers;
    outliers.seed = args.seed;
    pose_graph::ParseOutlierKind(args.outlier_kind, &outliers.kind);
    if (graph.num_vertices() < 3) {
      return ReportError(InvalidInput("--add-outliers needs a graph of >= 3 vertices", args.graph));
    }
    pose_graph::AddOutliers(graph, outliers);
  }

  nlohmann::json history = nlohmann::json::array();
  pose_graph::IterationCallback callback;
  if (args.verbose) {
    callback = [&](const pose_graph::IterationRecord& r) {
      if (args.json) {
        history.push_back({{"stage", r.stage},
                           {"iteration", r.iteration},
                           {"chi2", r.chi2},
                           {"seconds", r.seconds}});
      } else {
        std::printf("%-3s %4d  chi2=%.10g  t=%.6f s\n", r.stage.c_str(), r.iteration, r.chi2,
                    r.seconds);
      }
    };
  }
  if (!args.json) {
    std::printf("graph: %s (%zu vertices, %zu edges%s)\n", args.graph.c_str(), graph.num_vertices(),
                graph.num_edges(), chain ? ", odometry-chained initial guess" : "");
    std::printf("chi2_initial=%.10g method=%s\n", pose_graph::Chi2(graph), options.method.c_str());
    std::fflush(stdout);
  }
  const pose_graph::OptimizationReport report =
      pose_graph::Optimize(graph, options, args.iterations, callback);

  if (const Status s = io::WritePoseGraphFile(args.output, graph); !s.ok()) {
    return ReportError(s.error());
  }
  pose_graph::PoseErrors errors;
  if (reference) {
    errors = pose_graph::ComparePoses(graph, *reference);
  }
  if (args.json) {
    nlohmann::json out = {{"graph", args.graph},
                          {"output", args.output},
                          {"method", report.method},
                          {"vertices", graph.num_vertices()},
                          {"edges", graph.num_edges()},
                          {"components", report.components},
                          {"initial_guess", chain ? "odometry" : "file"},
                          {"chi2_initial", report.chi2_initial},
                          {"chi2_final", report.chi2_final},
                          {"iterations", report.iterations},
                          {"sgd_iterations", report.sgd_iterations},
                          {"ls_iterations", report.ls_iterations},
                          {"converged", report.converged},
                          {"seconds", report.seconds},
                          {"cpu_seconds", report.cpu_seconds},
                          {"initialization", options.initialization},
                          {"robust", options.robust.mechanism},
                          {"rejected_edges", report.rejected_edges},
                          {"chi2_inliers", report.chi2_inliers},
                          {"outliers_added", args.add_outliers}};
    if (reference) {
      out["mean_position_error"] = errors.mean_translation;
      out["max_position_error"] = errors.max_translation;
      out["mean_rotation_error"] = errors.mean_rotation;
    }
    if (args.verbose) {
      out["history"] = history;
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf(
        "chi2_final=%.10g iterations=%d (sgd %d, %s %d) seconds=%.6f cpu_seconds=%.6f "
        "components=%d\n",
        report.chi2_final, report.iterations, report.sgd_iterations,
        report.method == "lm" ? "lm" : "gn", report.ls_iterations, report.seconds,
        report.cpu_seconds, report.components);
    if (options.robust.mechanism != "none") {
      std::printf("robust=%s rejected_edges=%d chi2_inliers=%.10g\n",
                  options.robust.mechanism.c_str(), report.rejected_edges, report.chi2_inliers);
    }
    if (reference) {
      std::printf(
          "mean_position_error=%.6f m max_position_error=%.6f m mean_rotation_error=%.6f rad\n",
          errors.mean_translation, errors.max_translation, errors.mean_rotation);
    }
  }
  return kExitOk;
}

RunFunction SetupOptimize(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<OptimizeArgs>();
  sub.add_option("GRAPH", args->graph, "Input graph: g2o (.g2o) or TORO (.graph)")->required();
  sub.add_option("-o,--output", args->output, "Output graph: .g2o or .graph")->required();
  sub.add_option("--method", args->method, "sgd, gn, lm or sgd+gn (default: configuration)")
      ->check(CLI::IsMember({"sgd", "gn", "lm", "sgd+gn"}));
  sub.add_option("--iterations", args->iterations,
                 "Iterations: SGD for sgd, Gauss-Newton/LM otherwise (0 = configuration)")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--warmup", args->warmup, "SGD iterations before Gauss-Newton in sgd+gn")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--init", args->init,
                 "Initial guess: auto (file poses; odometry chain if vertices are missing), "
                 "file, or odometry")
      ->check(CLI::IsMember({"auto", "file", "odometry"}));
  sub.add_option("--sgd-tree", args->sgd_tree, "SGD spanning tree: bfs, chain or toro");
  sub.add_option("--sgd-variant", args->sgd_variant,
                 "SGD update: g2o (exact g2o error) or toro (TORO 2-D as published)");
  sub.add_option("--robust-kernel", args->robust_kernel,
                 "GN/LM kernel: none, huber, cauchy, dcs, geman_mcclure, truncated");
  sub.add_option("--robust-width", args->robust_width, "Kernel width [sqrt(chi2)]");
  sub.add_option("--robust-edges", args->robust_edges, "Edges the kernel applies to: loops, all")
      ->check(CLI::IsMember({"loops", "all"}));
  sub.add_option("--robust", args->robust,
                 "Wrong-loop-closure defence on loop edges: none, dcs or gnc")
      ->check(CLI::IsMember({"none", "dcs", "gnc"}));
  sub.add_option("--initialization", args->initialization,
                 "Orientation-first initial guess before optimizing: none, chordal or lago")
      ->check(CLI::IsMember({"none", "chordal", "lago"}));
  sub.add_option("--add-outliers", args->add_outliers,
                 "Benchmark: add N wrong loop closures before optimizing")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--outlier-kind", args->outlier_kind, "Benchmark: random, local or group")
      ->check(CLI::IsMember({"random", "local", "group"}));
  sub.add_option("--seed", args->seed, "Benchmark: seed of the outliers");
  sub.add_option("--reference", args->reference,
                 "Report the mean position error against this graph's poses (same vertices)");
  sub.add_flag("--json", args->json, "Print one JSON object");
  sub.add_flag("--verbose", args->verbose, "Print chi2 after every iteration");
  return [args](AppContext& ctx) { return RunOptimize(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "optimize", "Optimize a 2-D pose graph (g2o or TORO) with SGD, Gauss-Newton or LM",
    SetupOptimize});

}  // namespace
}  // namespace gridslam::app
