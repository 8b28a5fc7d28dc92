// Key-map alignment kernels (docs/design.md §1.5, §3.4): descriptor matching (own brute force vs
// OpenCV's BFMatcher), 2-point RANSAC with refinement, grid verification, and the whole Align()
// for two key maps of 200 features with 30 % true matches (issue target: <= 2 ms per pair).
#include <random>

#include <benchmark/benchmark.h>
#include <opencv2/features2d.hpp>

#include "gridslam/matching/align.hpp"
#include "gridslam/matching/internal/synthetic.hpp"

namespace gridslam::matching {
namespace {

const Pose2 kTwa(0.0, 0.2, 0.0);
const Pose2 kTwb(4.1, -0.1, 0.3);

// 200 vs 200 (or n vs n) features, 30 % of them seen by both maps, with the corridor grids.
struct Fixture {
  explicit Fixture(int n)
      : pair(internal::MakeFeaturePair(Between(kTwa, kTwb), n, n, (3 * n) / 10, 0.02, 7)),
        map_a(internal::MakeKeyMap(internal::CorridorWorld(), kTwa)),
        map_b(internal::MakeKeyMap(internal::CorridorWorld(), kTwb)) {}
  VerificationInput Input() const {
    return {map_b.obstacles, &map_a.distance, map_a.obstacles, &map_b.distance};
  }
  internal::SyntheticPair pair;
  internal::SyntheticKeyMap map_a;
  internal::SyntheticKeyMap map_b;
};

const Fixture& Get(int n) {
  static const Fixture f100(100);
  static const Fixture f200(200);
  static const Fixture f500(500);
  return n == 100 ? f100 : (n == 200 ? f200 : f500);
}

void BM_MatchDescriptors(benchmark::State& state) {
  const Fixture& f = Get(static_cast<int>(state.range(0)));
  const DescriptorMatchOptions options;
  for (auto _ : state) {
    benchmark::DoNotOptimize(MatchDescriptors(f.pair.a, f.pair.b, options));
  }
}
BENCHMARK(BM_MatchDescriptors)->Arg(100)->Arg(200)->Arg(500)->Unit(benchmark::kMicrosecond);

// The same association with OpenCV: knnMatch (k = 2) both ways, mutual check, ratio test.
void BM_OpenCvBFMatcherMutualRatio(benchmark::State& state) {
  const Fixture& f = Get(static_cast<int>(state.range(0)));
  cv::setNumThreads(1);
  const cv::BFMatcher matcher(cv::NORM_L2);
  for (auto _ : state) {
    std::vector<std::vector<cv::DMatch>> ab;
    std::vector<std::vector<cv::DMatch>> ba;
    matcher.knnMatch(f.pair.a.descriptors, f.pair.b.descriptors, ab, 2);
    matcher.knnMatch(f.pair.b.descriptors, f.pair.a.descriptors, ba, 2);
    std::vector<cv::DMatch> out;
    for (const auto& m : ab) {
      if (m.size() == 2 && m[0].distance < 0.9F * m[1].distance &&
          ba[static_cast<std::size_t>(m[0].trainIdx)][0].trainIdx == m[0].queryIdx) {
        out.push_back(m[0]);
      }
    }
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_OpenCvBFMatcherMutualRatio)
    ->Arg(100)
    ->Arg(200)
    ->Arg(500)
    ->Unit(benchmark::kMicrosecond);

void BM_MatchBinaryDescriptors(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(3);
  FeatureSet a;
  FeatureSet b;
  for (FeatureSet* s : {&a, &b}) {
    s->descriptors = cv::Mat(n, 32, CV_8U);
    cv::randu(s->descriptors, 0, 256);
    s->points.assign(static_cast<std::size_t>(n), Eigen::Vector2d::Zero());
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(MatchDescriptors(a, b, DescriptorMatchOptions{}));
  }
}
BENCHMARK(BM_MatchBinaryDescriptors)->Arg(200)->Arg(500)->Unit(benchmark::kMicrosecond);

void BM_OpenCvBFMatcherHamming(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  cv::setNumThreads(1);
  cv::Mat a(n, 32, CV_8U);
  cv::Mat b(n, 32, CV_8U);
  cv::randu(a, 0, 256);
  cv::randu(b, 0, 256);
  const cv::BFMatcher matcher(cv::NORM_HAMMING);
  for (auto _ : state) {
    std::vector<std::vector<cv::DMatch>> ab;
    std::vector<std::vector<cv::DMatch>> ba;
    matcher.knnMatch(a, b, ab, 2);
    matcher.knnMatch(b, a, ba, 2);
    benchmark::DoNotOptimize(ab);
  }
}
BENCHMARK(BM_OpenCvBFMatcherHamming)->Arg(200)->Arg(500)->Unit(benchmark::kMicrosecond);

Correspondences MatchedPoints(const Fixture& f, const std::vector<Match>& matches) {
  Correspondences c;
  for (const Match& m : matches) {
    c.a.push_back(f.pair.a.points[static_cast<std::size_t>(m.index_a)]);
    c.b.push_back(f.pair.b.points[static_cast<std::size_t>(m.index_b)]);
  }
  return c;
}

// RANSAC on the matches of the fixture (state.counters: matches, inliers, hypotheses), and on a
// harder input: the true matches plus as many random ones again (exhaustive_max_matches = 0).
void BM_Ransac(benchmark::State& state) {
  const Fixture& f = Get(static_cast<int>(state.range(0)));
  const std::vector<Match> matches = MatchDescriptors(f.pair.a, f.pair.b, {});
  const Correspondences c = MatchedPoints(f, matches);
  RansacResult r;
  for (auto _ : state) {
    r = EstimateRigidRansac(c, RansacOptions{});
    benchmark::DoNotOptimize(r);
  }
  state.counters["matches"] = static_cast<double>(c.size());
  state.counters["inliers"] = static_cast<double>(r.inliers.size());
  state.counters["hypotheses"] = r.iterations;
}
BENCHMARK(BM_Ransac)->Arg(200)->Arg(500)->Unit(benchmark::kMicrosecond);

void BM_RansacHalfOutliers(benchmark::State& state) {
  const Fixture& f = Get(200);
  Correspondences c = MatchedPoints(f, f.pair.truth);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-5.0, 5.0);
  const int n_true = c.size();
  for (int k = 0; k < static_cast<int>(state.range(0)) * n_true / 100; ++k) {
    c.a.emplace_back(pos(rng), pos(rng));
    c.b.emplace_back(pos(rng), pos(rng));
  }
  RansacOptions options;
  options.exhaustive_max_matches = 0;
  RansacResult r;
  for (auto _ : state) {
    r = EstimateRigidRansac(c, options);
    benchmark::DoNotOptimize(r);
  }
  state.counters["matches"] = static_cast<double>(c.size());
  state.counters["hypotheses"] = r.iterations;
}
BENCHMARK(BM_RansacHalfOutliers)->Arg(100)->Arg(400)->Unit(benchmark::kMicrosecond);

void BM_VerifyAlignment(benchmark::State& state) {
  const Fixture& f = Get(200);
  const VerificationInput input = f.Input();
  for (auto _ : state) {
    benchmark::DoNotOptimize(VerifyAlignment(Between(kTwa, kTwb), input, VerificationOptions{}));
  }
  state.counters["points"] =
      static_cast<double>(f.map_a.obstacles.size() + f.map_b.obstacles.size());
}
BENCHMARK(BM_VerifyAlignment)->Unit(benchmark::kMicrosecond);

// The whole pair: matching + RANSAC + refinement + information + verification both ways.
void BM_Align(benchmark::State& state) {
  const Fixture& f = Get(static_cast<int>(state.range(0)));
  const VerificationInput input = f.Input();
  AlignResult r;
  for (auto _ : state) {
    r = Align(f.pair.a, f.pair.b, AlignOptions{}, &input);
    benchmark::DoNotOptimize(r);
  }
  state.counters["accepted"] = r.accepted ? 1 : 0;
  state.counters["inliers"] = static_cast<double>(r.inliers.size());
}
BENCHMARK(BM_Align)->Arg(100)->Arg(200)->Arg(500)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gridslam::matching
