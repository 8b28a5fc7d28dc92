// Google Benchmark of the pose-graph back end (docs/design.md §3.4): one SGD iteration and one
// Gauss-Newton step (linearize, sparse Cholesky, solve, evaluate) on the shared graphs, from the
// odometry-chained guess. Graphs come from $GRIDSLAM_DATA/graphs; a missing one is skipped.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "gridslam/io/g2o_io.hpp"
#include "gridslam/pose_graph/gauss_newton.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"
#include "gridslam/pose_graph/sgd_optimizer.hpp"
#include "gridslam/testing/data_path.hpp"

namespace {

using gridslam::pose_graph::PoseGraph;

const char* const kGraphs[] = {"intel.g2o", "manhattan.g2o", "ais2klinik.g2o"};

// The graph at its odometry-chained guess, read once; null if the file is absent.
const PoseGraph* LoadGraph(const std::string& name) {
  static std::map<std::string, std::unique_ptr<PoseGraph>> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    std::unique_ptr<PoseGraph> graph;
    const auto path = gridslam::testing::DataDir() / "graphs" / name;
    if (std::filesystem::exists(path)) {
      auto read = gridslam::io::ReadPoseGraphFile(path.string());
      if (read.ok()) {
        graph = std::make_unique<PoseGraph>(std::move(read).value());
        gridslam::pose_graph::InitializeByChaining(*graph);
      }
    }
    it = cache.emplace(name, std::move(graph)).first;
  }
  return it->second.get();
}

void BM_SgdIteration(benchmark::State& state) {
  const std::string name = kGraphs[state.range(0)];
  const PoseGraph* graph = LoadGraph(name);
  if (graph == nullptr) {
    state.SkipWithError((name + " not found in $GRIDSLAM_DATA/graphs").c_str());
    return;
  }
  state.SetLabel(name);
  gridslam::pose_graph::SgdOptimizer sgd(*graph, {});
  for (auto _ : state) {
    sgd.Iterate(1);
  }
  state.counters["path_length"] = static_cast<double>(sgd.TotalPathLength());
}

void BM_GaussNewtonStep(benchmark::State& state) {
  const std::string name = kGraphs[state.range(0)];
  const PoseGraph* source = LoadGraph(name);
  if (source == nullptr) {
    state.SkipWithError((name + " not found in $GRIDSLAM_DATA/graphs").c_str());
    return;
  }
  state.SetLabel(name);
  PoseGraph graph = *source;
  gridslam::pose_graph::GaussNewtonSolver solver(graph, gridslam::pose_graph::EffectiveFixed(graph),
                                                 {});
  for (auto _ : state) {
    benchmark::DoNotOptimize(solver.Run(graph, /*levenberg=*/false, /*max_iterations=*/1));
  }
}

void BM_GaussNewtonSetup(benchmark::State& state) {
  const std::string name = kGraphs[state.range(0)];
  const PoseGraph* graph = LoadGraph(name);
  if (graph == nullptr) {
    state.SkipWithError((name + " not found in $GRIDSLAM_DATA/graphs").c_str());
    return;
  }
  state.SetLabel(name);
  const std::vector<bool> fixed = gridslam::pose_graph::EffectiveFixed(*graph);
  for (auto _ : state) {
    // Ordering (AMD on 3x3 blocks), elimination tree and symbolic factorization.
    gridslam::pose_graph::GaussNewtonSolver solver(*graph, fixed, {});
    benchmark::DoNotOptimize(&solver);
  }
}

BENCHMARK(BM_SgdIteration)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GaussNewtonStep)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GaussNewtonSetup)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

}  // namespace
