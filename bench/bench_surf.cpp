// SURF on key-map distance images (docs/design.md §1.4; issue target: description <= 10 ms per key
// map including the distance transform). Synthetic 300 × 300 and 400 × 400 distance images
// (walls drawn with cv::line, cv::distanceTransform, clamped at 30 px to 8 bit): the project's
// SURF-64 (integral image, Fast-Hessian, orientation, descriptor, and the stages alone), U-SURF,
// SURF-128, the whole description from the obstacle image, and OpenCV's SIFT, ORB and AKAZE on the
// same image for reference (OpenCV limited to one thread). Counter `keypoints` = features per
// image. The key-map side of the description: the geometry (distance field and obstacle points)
// of a synthetic key map's cells, and its whole description.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/features2d.hpp>

#include "gridslam/description/key_map_cells.hpp"
#include "gridslam/description/keymap_describer.hpp"
#include "gridslam/features/fast_hessian.hpp"
#include "gridslam/features/integral_image.hpp"
#include "gridslam/features/surf_descriptor.hpp"
#include "gridslam/features/surf_feature2d.hpp"
#include "gridslam/features/synthetic_keymap.hpp"
#include "gridslam/keymap/key_map.hpp"

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

// A synthetic key map of `size` pixels, its integral image and its detected keypoints: the
// set-up of the benchmarks that time the work done per keypoint.
struct DetectedKeyMap {
  explicit DetectedKeyMap(int size)
      : integral(gridslam::features::MakeSyntheticKeyMap(size, 1)),
        keypoints(gridslam::features::DetectFastHessian(integral, SurfOptions{})) {}
  const gridslam::features::IntegralImage integral;
  const std::vector<cv::KeyPoint> keypoints;
};

void BM_OrientationAndDescriptor(benchmark::State& state) {
  const DetectedKeyMap detected(static_cast<int>(state.range(0)));
  const gridslam::features::IntegralImage& integral = detected.integral;
  const std::vector<cv::KeyPoint>& keypoints = detected.keypoints;
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

// The orientation and the descriptor alone, at the detected keypoints.
void BM_AssignOrientation(benchmark::State& state) {
  const DetectedKeyMap detected(static_cast<int>(state.range(0)));
  const gridslam::features::IntegralImage& integral = detected.integral;
  const std::vector<cv::KeyPoint>& keypoints = detected.keypoints;
  for (auto _ : state) {
    for (const cv::KeyPoint& kp : keypoints) {
      benchmark::DoNotOptimize(gridslam::features::AssignOrientation(
          integral, kp.pt.x, kp.pt.y, gridslam::features::ScaleOfSize(kp.size)));
    }
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

void BM_SurfDescriptor(benchmark::State& state) {
  const DetectedKeyMap detected(static_cast<int>(state.range(0)));
  const gridslam::features::IntegralImage& integral = detected.integral;
  const std::vector<cv::KeyPoint>& keypoints = detected.keypoints;
  std::vector<float> descriptor(gridslam::features::kSurfDescriptorSize);
  for (auto _ : state) {
    for (const cv::KeyPoint& kp : keypoints) {
      // A fixed, non-trivial orientation: the rotated sampling grid as in the pipeline.
      gridslam::features::ComputeSurfDescriptor(integral, kp.pt.x, kp.pt.y,
                                                gridslam::features::ScaleOfSize(kp.size), 0.7F,
                                                false, descriptor.data());
      benchmark::DoNotOptimize(descriptor.data());
    }
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

// Cells of a synthetic key map at 5 cm: the walls are obstacles, the disc the sensor covered is
// free, the corners beyond it unknown.
gridslam::Grid2D<float> SyntheticLogOdds(int size) {
  const cv::Mat obstacles = gridslam::features::RenderObstacleImage(
      gridslam::features::MakeSyntheticWalls(size, 1), size);
  gridslam::Grid2D<float> log_odds(gridslam::MapLimits(0.05, Eigen::Vector2d::Zero(), size, size),
                                   0.0F);
  const double radius = 0.45 * size;
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const double r = std::hypot(i - 0.5 * size, j - 0.5 * size);
      if (obstacles.at<std::uint8_t>(j, i) == 0) {
        log_odds(i, j) = 2.0F;
      } else if (r < radius) {
        log_odds(i, j) = -1.0F;
      }
    }
  }
  return log_odds;
}

gridslam::description::KeyMapCells SyntheticCells(int size) {
  return {SyntheticLogOdds(size), 0.62F, 0.05F};
}

void BM_KeyMapGeometry(benchmark::State& state) {
  const gridslam::description::KeyMapCells cells = SyntheticCells(static_cast<int>(state.range(0)));
  gridslam::distance_transform::SquaredDistanceField field;
  gridslam::description::SquaredObstacleDistances(cells, field);
  for (auto _ : state) {
    const gridslam::description::KeyMapGeometry geometry =
        gridslam::description::ComputeGeometry(cells, field);
    benchmark::DoNotOptimize(geometry.distance.data());
  }
}

// KeyMapDescriber::Describe of the synthetic key map: cells, distance transform, images,
// geometry and SURF, as the pipeline describes each key map.
void BM_DescribeCells(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  gridslam::keymap::KeyMap key_map;
  key_map.log_odds = SyntheticLogOdds(size);
  const gridslam::description::KeyMapDescriber describer(
      gridslam::description::DescriptionOptions{});
  std::size_t features = 0;
  for (auto _ : state) {
    const gridslam::description::KeyMapDescription description = describer.Describe(key_map);
    features = description.features.points.size();
    benchmark::DoNotOptimize(description.distance.data());
  }
  state.counters["keypoints"] = static_cast<double>(features);
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
BENCHMARK(BM_AssignOrientation)->Arg(300)->Arg(400)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SurfDescriptor)->Arg(300)->Arg(400)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KeyMapGeometry)->Arg(300)->Arg(400)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DescribeCells)->Arg(300)->Arg(400)->Unit(benchmark::kMicrosecond);
