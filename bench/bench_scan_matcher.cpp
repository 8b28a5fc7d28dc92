// The front end's kernels at the real sizes (docs/design.md §3.4): one scan match (Gauss-Newton on
// the distance field, from a prior 5 cm / 1 degree off) and one scan insertion (ray casting into
// the log-odds window), for 180- and 360-beam scans and 15 m / 20 m windows (301^2 / 401^2 cells),
// plus the incremental distance-field update that follows an insertion. The scans come from the
// analytic test world of the scan matcher's tests, with 1 cm range noise.
#include <benchmark/benchmark.h>

#include "gridslam/scan_matching/internal/synthetic_world.hpp"
#include "gridslam/scan_matching/scan_matcher.hpp"

namespace {

using gridslam::LocalMapOptions;
using gridslam::Pose2;
using gridslam::RollingWindow;
using gridslam::ScanPoints;
using gridslam::scan_matching::MatchingField;
using gridslam::scan_matching::ScanMatcher;
using gridslam::scan_matching::ScanMatcherOptions;
using gridslam::scan_matching::internal::SimulateScan;
using gridslam::scan_matching::internal::TestWorld;

// A window built from scans along a path through the test world.
struct Scene {
  Scene(int beams, double size, const std::string& residual)
      : window(Options(size), {6.0, 3.5}, residual == "point_to_line"), field(0.3) {
    for (int k = 0; k < 40; ++k) {
      const Pose2 pose(2.0 + 0.15 * k, 1.5 + 0.05 * k, 0.02 * k);
      window.InsertScan(pose, Points(pose, beams, static_cast<unsigned>(k)));
    }
    field.Update(window);
    window.ClearChanges();
  }
  static LocalMapOptions Options(double size) {
    LocalMapOptions options;
    options.size = size;
    return options;
  }
  static ScanPoints Points(const Pose2& pose, int beams, unsigned seed) {
    return ExtractScanPoints(SimulateScan(TestWorld(), pose, beams, 30.0, 0.01, seed), Pose2(),
                             30.0);
  }
  RollingWindow window;
  MatchingField field;
};

void BM_ScanMatch(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  const double size = static_cast<double>(state.range(1));
  const std::string residual = state.range(2) == 0 ? "distance_field" : "point_to_line";
  const Scene scene(beams, size, residual);
  ScanMatcherOptions options;
  options.residual = residual;
  const ScanMatcher matcher(options);
  const Pose2 truth(5.0, 2.9, 0.5);
  const ScanPoints scan = Scene::Points(truth, beams, 99);
  const Pose2 prior = truth * Pose2(0.04, -0.03, 0.017);
  const Eigen::Matrix3d information = Eigen::Vector3d(400.0, 400.0, 400.0).asDiagonal();
  gridslam::scan_matching::MatchResult result;
  for (auto _ : state) {
    result = matcher.Match(scene.window, scene.field, scan, prior, information);
    benchmark::DoNotOptimize(result.T_odom_base);
  }
  state.counters["iterations"] = result.iterations;
  state.counters["searched"] = result.searched ? 1.0 : 0.0;
  state.counters["error_mm"] =
      1000.0 * (result.T_odom_base.translation() - truth.translation()).norm();
}
BENCHMARK(BM_ScanMatch)
    ->ArgNames({"beams", "window_m", "point_to_line"})
    ->Args({180, 15, 0})
    ->Args({360, 15, 0})
    ->Args({180, 20, 0})
    ->Args({360, 20, 0})
    ->Args({360, 20, 1})
    ->Unit(benchmark::kMicrosecond);

void BM_ScanInsert(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  const double size = static_cast<double>(state.range(1));
  Scene scene(beams, size, "distance_field");
  const Pose2 pose(5.0, 2.9, 0.5);
  const ScanPoints scan = Scene::Points(pose, beams, 7);
  for (auto _ : state) {
    scene.window.InsertScan(pose, scan);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ScanInsert)
    ->ArgNames({"beams", "window_m"})
    ->Args({180, 15})
    ->Args({360, 15})
    ->Args({180, 20})
    ->Args({360, 20})
    ->Unit(benchmark::kMicrosecond);

// Insertion of a scan from a new pose followed by the incremental distance-field update.
void BM_InsertAndUpdateField(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  Scene scene(beams, 20.0, "distance_field");
  int k = 0;
  for (auto _ : state) {
    const Pose2 pose(3.0 + 0.05 * (k % 80), 2.9, 0.01 * (k % 50));
    scene.window.InsertScan(pose, Scene::Points(pose, beams, static_cast<unsigned>(k)));
    scene.field.Update(scene.window);
    scene.window.ClearChanges();
    ++k;
  }
}
BENCHMARK(BM_InsertAndUpdateField)
    ->ArgNames({"beams"})
    ->Arg(180)
    ->Arg(360)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
