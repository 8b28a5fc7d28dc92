// The kernels issue 19 changed (docs/speed.md), each beside what it replaced, on inputs sized like
// the real work: recomputing a key map's geometry from its two bits per cell (what a cache miss
// costs), the unlabelled distance transform (integer row pass) vs the labelled one (float
// envelope) on a 301^2 key map, and the tiled global fusion with 1 and 2 threads vs the dense
// one. Each pair gives the same numbers (tested in the modules' unit tests).
#include <cmath>
#include <numbers>
#include <random>

#include <benchmark/benchmark.h>

#include "gridslam/description/key_map_cells.hpp"
#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/fusion/global_grid.hpp"

namespace {

using namespace gridslam;  // NOLINT(google-build-using-namespace): a benchmark file

// A 301^2 key map: a room with walls, observed within 7 m of its centre.
Grid2D<float> KeyMapLogOdds() {
  const MapLimits limits(0.05, Eigen::Vector2d(-7.525, -7.525), 301, 301);
  Grid2D<float> log_odds(limits, 0.0F);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-6.5, 6.5);
  for (int j = 0; j < 301; ++j) {
    for (int i = 0; i < 301; ++i) {
      const Eigen::Vector2d p = limits.CellCenter({i, j});
      if (p.norm() < 7.0) {
        log_odds(i, j) = -2.0F;
      }
    }
  }
  for (int wall = 0; wall < 12; ++wall) {
    const Eigen::Vector2d a(u(rng), u(rng));
    const Eigen::Vector2d b(u(rng), u(rng));
    for (double t = 0.0; t <= 1.0; t += 0.002) {
      const Eigen::Array2i c = limits.CellIndex(a + t * (b - a));
      if (limits.Contains(c)) {
        log_odds.at(c) = 3.0F;
      }
    }
  }
  return log_odds;
}

void BM_KeyMapGeometryRecomputed(benchmark::State& state) {
  const description::KeyMapCells cells(KeyMapLogOdds(), 0.62F, 0.05F);
  for (auto _ : state) {
    const description::KeyMapGeometry g = description::ComputeGeometry(cells);
    benchmark::DoNotOptimize(g.distance.data());
  }
  state.counters["cells_bytes"] = static_cast<double>(cells.Bytes());
  state.counters["geometry_bytes"] =
      static_cast<double>(description::ComputeGeometry(cells).Bytes());
}
BENCHMARK(BM_KeyMapGeometryRecomputed)->Unit(benchmark::kMicrosecond);

void BM_DistanceTransform(benchmark::State& state) {
  const description::KeyMapCells cells(KeyMapLogOdds(), 0.62F, 0.05F);
  std::vector<std::uint8_t> sources(301 * 301);
  for (int j = 0; j < 301; ++j) {
    for (int i = 0; i < 301; ++i) {
      sources[static_cast<std::size_t>(j * 301 + i)] = cells.Obstacle(i, j) ? 1 : 0;
    }
  }
  const bool labels = state.range(0) != 0;
  distance_transform::SquaredDistanceField field;
  for (auto _ : state) {
    distance_transform::SquaredEuclideanDistanceTransform(sources.data(), 301, 301, field, labels);
    benchmark::DoNotOptimize(field.squared.data());
  }
}
BENCHMARK(BM_DistanceTransform)
    ->ArgNames({"labels"})
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMicrosecond);

struct ScanFixture {
  ScanFixture() : laser(3000) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> range(0.5F, 12.0F);
    for (std::size_t k = 0; k < laser.size(); ++k) {
      LaserScan& scan = laser[k];
      scan.angle_min = -std::numbers::pi / 2;
      scan.angle_increment = std::numbers::pi / 360.0;
      scan.range_min = 0.1;
      scan.range_max = 30.0;
      for (int b = 0; b <= 360; ++b) {
        scan.ranges.push_back(range(rng));
      }
      const double s = 0.02 * static_cast<double>(k);
      scans.push_back(
          {Pose2(20.0 * std::cos(0.05 * s), 20.0 * std::sin(0.05 * s), s), Pose2(), &scan});
    }
    options.min_motion = 0.0;
    options.min_rotation = 0.0;
  }
  std::vector<LaserScan> laser;
  std::vector<fusion::PosedScan> scans;
  fusion::FusionOptions options;
};

const ScanFixture& Scans() {
  static const ScanFixture f;
  return f;
}

void BM_FuseScansDense(benchmark::State& state) {
  const ScanFixture& f = Scans();
  for (auto _ : state) {
    const Grid2D<float> grid = fusion::FuseScans(f.scans, f.options);
    benchmark::DoNotOptimize(grid.data());
  }
}
BENCHMARK(BM_FuseScansDense)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FuseScansTiled(benchmark::State& state) {
  const ScanFixture& f = Scans();
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const TiledGrid<float> grid = fusion::FuseScansTiled(f.scans, f.options, threads);
    benchmark::DoNotOptimize(grid.Tile(0, 0));
  }
}
BENCHMARK(BM_FuseScansTiled)
    ->ArgNames({"threads"})
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
