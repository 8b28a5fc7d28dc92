// Exact Euclidean distance transform (Felzenszwalb-Huttenlocher) on grids of the key-map sizes
// (241^2, 301^2, 500^2 cells) against OpenCV's cv::distanceTransform(DIST_L2, DIST_MASK_PRECISE),
// which computes the same exact distances. The input imitates an indoor key map: a few percent of
// the cells are obstacles, laid out as random wall segments.
#include <cmath>
#include <random>

#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"

namespace {

using gridslam::distance_transform::SquaredDistanceField;

// 255 = free, 0 = obstacle (OpenCV's convention).
cv::Mat WallImage(int side) {
  std::mt19937 rng(5);
  cv::Mat image(side, side, CV_8U, cv::Scalar(255));
  std::uniform_int_distribution<int> coord(0, side - 1);
  for (int k = 0; k < side / 8; ++k) {
    cv::line(image, {coord(rng), coord(rng)}, {coord(rng), coord(rng)}, cv::Scalar(0), 1);
  }
  return image;
}

void BM_FelzenszwalbHuttenlocher(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const bool labels = state.range(1) != 0;
  const cv::Mat image = WallImage(side);
  const cv::Mat sources = (image == 0);
  SquaredDistanceField field;
  for (auto _ : state) {
    gridslam::distance_transform::SquaredEuclideanDistanceTransform(sources.ptr<std::uint8_t>(),
                                                                    side, side, field, labels);
    benchmark::DoNotOptimize(field.squared.data());
  }
  state.SetItemsProcessed(state.iterations() * side * side);
}
BENCHMARK(BM_FelzenszwalbHuttenlocher)
    ->ArgNames({"side", "labels"})
    ->Args({241, 0})
    ->Args({301, 0})
    ->Args({301, 1})
    ->Args({500, 0})
    ->Unit(benchmark::kMicrosecond);

void BM_FelzenszwalbHuttenlocherTruncated(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const cv::Mat sources = (WallImage(side) == 0);
  SquaredDistanceField field;
  for (auto _ : state) {
    gridslam::distance_transform::SquaredEuclideanDistanceTransform(sources.ptr<std::uint8_t>(),
                                                                    side, side, field, true, 10.0F);
    benchmark::DoNotOptimize(field.squared.data());
  }
  state.SetItemsProcessed(state.iterations() * side * side);
}
BENCHMARK(BM_FelzenszwalbHuttenlocherTruncated)
    ->ArgNames({"side"})
    ->Arg(301)
    ->Unit(benchmark::kMicrosecond);

void BM_DistanceTransformCells(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const cv::Mat image = WallImage(side);
  for (auto _ : state) {
    cv::Mat d = gridslam::distance_transform::DistanceTransformCells(image);
    benchmark::DoNotOptimize(d.data);
  }
  state.SetItemsProcessed(state.iterations() * side * side);
}
BENCHMARK(BM_DistanceTransformCells)->ArgNames({"side"})->Arg(301)->Unit(benchmark::kMicrosecond);

void BM_OpenCvPrecise(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const cv::Mat image = WallImage(side);
  cv::setNumThreads(1);
  cv::Mat d;
  for (auto _ : state) {
    cv::distanceTransform(image, d, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    benchmark::DoNotOptimize(d.data);
  }
  state.SetItemsProcessed(state.iterations() * side * side);
}
BENCHMARK(BM_OpenCvPrecise)
    ->ArgNames({"side"})
    ->Arg(241)
    ->Arg(301)
    ->Arg(500)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
