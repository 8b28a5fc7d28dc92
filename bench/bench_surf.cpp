// SURF on key-map distance images (docs/design.md §1.4; issue target: description <= 10 ms per key
// map including the distance transform). Synthetic 300 × 300 and 400 × 400 distance images
// (walls drawn with cv::line, cv::distanceTransform, clamped at 30 px to 8 bit): the project's
// SURF-64 (integral image, Fast-Hessian, orientation, descriptor, and the stages alone), U-SURF,
// SURF-128, the whole description from the obstacle image, and OpenCV's SIFT, ORB and AKAZE on the
// same image for reference (OpenCV limited to one thread). Counter `keypoints` = features per
// image.
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/features2d.hpp>

#include "gridslam/features/fast_hessian.hpp"
#include "gridslam/features/integral_image.hpp"
#include "gridslam/features/surf_descriptor.hpp"
#include "gridslam/features/surf_feature2d.hpp"
#include "gridslam/features/synthetic_keymap.hpp"

namespace {

using gridslam::features::SurfOptions;

void DetectAndDescribe(benchmark::State& state, const cv::Ptr<cv::Feature2D>& detector) {
  cv::setNumThreads(1);  // single-threaded like the project's SURF, for a fair comparison
  const cv::Mat image =
      gridslam::features::MakeSyntheticKeyMap(static_cast<int>(state.range(0)), 1);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (auto _ : state) {
    detector->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
    benchmark::DoNotOptimize(descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

void BM_Surf64(benchmark::State& state) {
  DetectAndDescribe(state, gridslam::features::SurfFeature2D::Create(SurfOptions{}));
}

void BM_USurf64(benchmark::State& state) {
  SurfOptions options;
  options.upright = true;
  DetectAndDescribe(state, gridslam::features::SurfFeature2D::Create(options));
}

void BM_Surf128(benchmark::State& state) {
  SurfOptions options;
  options.extended = true;
  DetectAndDescribe(state, gridslam::features::SurfFeature2D::Create(options));
}

void BM_OpenCv(benchmark::State& state, const std::string& name) {
  DetectAndDescribe(state, gridslam::features::CreateDetector(name, SurfOptions{}).value());
}

// The key map's whole description: obstacle image -> clamped distance image -> SURF-64.
void BM_DescribeKeyMap(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const cv::Mat obstacles = gridslam::features::RenderObstacleImage(
      gridslam::features::MakeSyntheticWalls(size, 1), size);
  const cv::Ptr<cv::Feature2D> surf = gridslam::features::SurfFeature2D::Create(SurfOptions{});
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (auto _ : state) {
    const cv::Mat image = gridslam::features::DistanceImage8U(obstacles, 30.0);
    surf->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
    benchmark::DoNotOptimize(descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

// The stages alone.
void BM_IntegralImage(benchmark::State& state) {
  const cv::Mat image =
      gridslam::features::MakeSyntheticKeyMap(static_cast<int>(state.range(0)), 1);
  gridslam::features::IntegralImage integral;
  for (auto _ : state) {
    integral.Compute(image);
    benchmark::DoNotOptimize(integral.Row(0));
  }
}

void BM_FastHessian(benchmark::State& state) {
  const gridslam::features::IntegralImage integral(
      gridslam::features::MakeSyntheticKeyMap(static_cast<int>(state.range(0)), 1));
  std::vector<cv::KeyPoint> keypoints;
  for (auto _ : state) {
    keypoints = gridslam::features::DetectFastHessian(integral, SurfOptions{});
    benchmark::DoNotOptimize(keypoints.data());
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

void BM_OrientationAndDescriptor(benchmark::State& state) {
  const gridslam::features::IntegralImage integral(
      gridslam::features::MakeSyntheticKeyMap(static_cast<int>(state.range(0)), 1));
  const std::vector<cv::KeyPoint> keypoints =
      gridslam::features::DetectFastHessian(integral, SurfOptions{});
  std::vector<float> descriptor(gridslam::features::kSurfDescriptorSize);
  for (auto _ : state) {
    for (const cv::KeyPoint& kp : keypoints) {
      const float scale = gridslam::features::ScaleOfSize(kp.size);
      const float angle = gridslam::features::AssignOrientation(integral, kp.pt.x, kp.pt.y, scale);
      gridslam::features::ComputeSurfDescriptor(integral, kp.pt.x, kp.pt.y, scale, angle, false,
                                                descriptor.data());
      benchmark::DoNotOptimize(descriptor.data());
    }
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

}  // namespace

BENCHMARK(BM_Surf64)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_USurf64)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Surf128)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DescribeKeyMap)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OpenCv, sift, std::string("sift"))
    ->Arg(300)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OpenCv, orb, std::string("orb"))
    ->Arg(300)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OpenCv, akaze, std::string("akaze"))
    ->Arg(300)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IntegralImage)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FastHessian)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OrientationAndDescriptor)->Arg(300)->Arg(400)->Unit(benchmark::kMillisecond);
