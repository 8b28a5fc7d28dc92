// Invariance of the project's SURF on synthetic key-map distance images (walls drawn with
// cv::line, cv::distanceTransform, clamped to 8 bit): keypoints repeat, descriptors match and the
// rigid transform fitted to the matches recovers the rotation within 1° under rotations (30°, 90°,
// 137°) and shifts, of the warped image and of the walls drawn anew.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "gridslam/features/fast_hessian.hpp"
#include "gridslam/features/surf_feature2d.hpp"
#include "gridslam/features/synthetic_keymap.hpp"

namespace gridslam::features {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kSize = 300;

// A rigid image transform q = R(theta)·p + t, theta in the image frame (y down).
struct Rigid {
  double theta = 0.0;
  cv::Point2d t;
  [[nodiscard]] cv::Point2d operator*(cv::Point2d p) const {
    return {std::cos(theta) * p.x - std::sin(theta) * p.y + t.x,
            std::sin(theta) * p.x + std::cos(theta) * p.y + t.y};
  }
};

// Least-squares rigid fit b ≈ T_b_a·a (2-D Kabsch, no scale).
Rigid FitRigid(const std::vector<cv::Point2d>& a, const std::vector<cv::Point2d>& b) {
  cv::Point2d ca;
  cv::Point2d cb;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ca += a[i];
    cb += b[i];
  }
  ca *= 1.0 / static_cast<double>(a.size());
  cb *= 1.0 / static_cast<double>(b.size());
  double dot = 0.0;
  double cross = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const cv::Point2d p = a[i] - ca;
    const cv::Point2d q = b[i] - cb;
    dot += p.x * q.x + p.y * q.y;
    cross += p.x * q.y - p.y * q.x;
  }
  Rigid T_b_a{std::atan2(cross, dot), {}};
  T_b_a.t = cb - T_b_a * ca;
  return T_b_a;
}

// Exhaustive 2-point hypotheses over the matches, the one with most inliers (within
// inlier_px) refined by least squares on its inliers.
struct RobustFit {
  Rigid T_b_a;
  int inliers = 0;
};
RobustFit FitRigidRobust(const std::vector<cv::Point2d>& a, const std::vector<cv::Point2d>& b,
                         double inlier_px) {
  RobustFit best;
  std::vector<cv::Point2d> best_a;
  std::vector<cv::Point2d> best_b;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = i + 1; j < a.size(); ++j) {
      if (cv::norm(a[j] - a[i]) < 20.0) {
        continue;
      }
      const Rigid T_b_a = FitRigid({a[i], a[j]}, {b[i], b[j]});
      std::vector<cv::Point2d> in_a;
      std::vector<cv::Point2d> in_b;
      for (std::size_t k = 0; k < a.size(); ++k) {
        if (cv::norm(T_b_a * a[k] - b[k]) < inlier_px) {
          in_a.push_back(a[k]);
          in_b.push_back(b[k]);
        }
      }
      if (static_cast<int>(in_a.size()) > best.inliers) {
        best.inliers = static_cast<int>(in_a.size());
        best_a = in_a;
        best_b = in_b;
      }
    }
  }
  if (best.inliers >= 2) {
    best.T_b_a = FitRigid(best_a, best_b);
  }
  return best;
}

// Image b: image a rotated by `deg` (counter-clockwise on screen, as cv::getRotationMatrix2D)
// about its centre and shifted; the border takes the clamp value, like far free space.
struct ImagePair {
  cv::Mat a;
  cv::Mat b;
  Rigid T_b_a;
};
ImagePair Transformed(const cv::Mat& a, double deg, cv::Point2d shift) {
  const cv::Point2d c((a.cols - 1) / 2.0, (a.rows - 1) / 2.0);
  cv::Mat m = cv::getRotationMatrix2D(c, deg, 1.0);
  m.at<double>(0, 2) += shift.x;
  m.at<double>(1, 2) += shift.y;
  ImagePair pair{a, {}, {}};
  cv::warpAffine(a, pair.b, m, a.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(255));
  pair.T_b_a.theta = std::atan2(m.at<double>(1, 0), m.at<double>(0, 0));
  pair.T_b_a.t = {m.at<double>(0, 2), m.at<double>(1, 2)};
  return pair;
}

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};
Features Describe(const cv::Ptr<cv::Feature2D>& detector, const cv::Mat& image) {
  Features f;
  detector->detectAndCompute(image, cv::noArray(), f.keypoints, f.descriptors);
  return f;
}

// True if the Fast-Hessian search of the keypoint's octave covers point p in an image.
bool Searchable(const cv::KeyPoint& kp, cv::Point2d p, const SurfOptions& options) {
  const int step = options.initial_step << kp.octave;
  const int margin = (FilterSize(kp.octave, options.layers_per_octave - 1) - 1) / 2 + step;
  return p.x >= margin && p.y >= margin && p.x <= kSize - 1 - margin && p.y <= kSize - 1 - margin;
}

// Fraction of a's keypoints, searchable at their mapped place in b, that b repeats: a keypoint
// within max(1.5 px, 0.4 s), filter size within 35 %, same sign of the Laplacian.
double Repeatability(const Features& a, const Features& b, const Rigid& T_b_a,
                     const SurfOptions& options) {
  int total = 0;
  int repeated = 0;
  for (const cv::KeyPoint& ka : a.keypoints) {
    const cv::Point2d q = T_b_a * cv::Point2d(ka.pt);
    if (!Searchable(ka, q, options)) {
      continue;
    }
    ++total;
    const double radius = std::max(1.5, 0.4 * ScaleOfSize(ka.size));
    for (const cv::KeyPoint& kb : b.keypoints) {
      if (cv::norm(cv::Point2d(kb.pt) - q) <= radius &&
          std::abs(std::log(kb.size / ka.size)) <= 0.35 && kb.class_id == ka.class_id) {
        ++repeated;
        break;
      }
    }
  }
  return total == 0 ? 0.0 : static_cast<double>(repeated) / total;
}

// Mutual nearest neighbours (cv::BFMatcher with cross-check), the number of them that are
// correct (within 2 px of the true place), and the rigid transform fitted to them robustly.
struct MatchResult {
  int mutual = 0;
  int correct = 0;
  RobustFit fit;
};
MatchResult Match(const Features& a, const Features& b, const Rigid& T_b_a) {
  cv::BFMatcher matcher(cv::NORM_L2, /*crossCheck=*/true);
  std::vector<cv::DMatch> matches;
  matcher.match(a.descriptors, b.descriptors, matches);
  MatchResult r;
  std::vector<cv::Point2d> pa;
  std::vector<cv::Point2d> pb;
  for (const cv::DMatch& m : matches) {
    pa.emplace_back(a.keypoints[static_cast<std::size_t>(m.queryIdx)].pt);
    pb.emplace_back(b.keypoints[static_cast<std::size_t>(m.trainIdx)].pt);
    r.correct += cv::norm(T_b_a * pa.back() - pb.back()) < 2.0 ? 1 : 0;
  }
  r.mutual = static_cast<int>(matches.size());
  r.fit = FitRigidRobust(pa, pb, 2.0);
  return r;
}

struct Case {
  double deg;
  cv::Point2d shift;
  bool rerender = false;  // b drawn from the transformed walls instead of warping a
};

// Image b drawn from the walls moved by the same transform as Transformed(): the walls are
// rasterised anew, as in two key maps of one place.
ImagePair Rerendered(std::uint32_t seed, double deg, cv::Point2d shift) {
  const std::vector<cv::Vec4f> walls = MakeSyntheticWalls(kSize, seed);
  ImagePair pair = Transformed(MakeSyntheticKeyMap(kSize, seed), deg, shift);
  const Rigid& T_b_a = pair.T_b_a;
  const cv::Matx23d m(std::cos(T_b_a.theta), -std::sin(T_b_a.theta), T_b_a.t.x,
                      std::sin(T_b_a.theta), std::cos(T_b_a.theta), T_b_a.t.y);
  pair.b = DistanceImage8U(RenderObstacleImage(walls, kSize, m), 30.0);
  return pair;
}

struct Expect {
  double repeatability;  // per image pair, at least
  double precision;      // correct / mutual matches, at least
};

class SurfInvarianceTest : public ::testing::TestWithParam<std::pair<Case, Expect>> {};

TEST_P(SurfInvarianceTest, RepeatableMatchingAndRotationRecovered) {
  const auto [c, expect] = GetParam();
  SurfOptions options;
  const cv::Ptr<cv::Feature2D> surf = SurfFeature2D::Create(options);
  for (const std::uint32_t seed : {1U, 2U, 3U}) {
    const ImagePair pair = c.rerender
                               ? Rerendered(seed, c.deg, c.shift)
                               : Transformed(MakeSyntheticKeyMap(kSize, seed), c.deg, c.shift);
    const Features fa = Describe(surf, pair.a);
    const Features fb = Describe(surf, pair.b);
    const double repeatability = Repeatability(fa, fb, pair.T_b_a, options);
    const MatchResult m = Match(fa, fb, pair.T_b_a);
    const double angle_error = std::remainder(m.fit.T_b_a.theta - pair.T_b_a.theta, 2.0 * kPi);
    const cv::Point2d centre(kSize / 2.0, kSize / 2.0);
    const double centre_error = cv::norm(m.fit.T_b_a * centre - pair.T_b_a * centre);
    std::printf(
        "%s %.0f deg seed %u: %zu/%zu keypoints, repeatability %.2f, mutual %d, correct %d, "
        "inliers %d, angle error %.3f deg, centre error %.2f px\n",
        c.rerender ? "drawn" : "warped", c.deg, seed, fa.keypoints.size(), fb.keypoints.size(),
        repeatability, m.mutual, m.correct, m.fit.inliers, angle_error * 180.0 / kPi, centre_error);
    EXPECT_GE(fa.keypoints.size(), 40U) << seed;
    EXPECT_GE(repeatability, expect.repeatability) << seed;
    EXPECT_GE(m.correct, 20) << seed;
    EXPECT_GE(static_cast<double>(m.correct) / m.mutual, expect.precision) << seed;
    EXPECT_GE(m.fit.inliers, m.correct - 2) << seed;
    EXPECT_LT(std::abs(angle_error), 1.0 * kPi / 180.0) << seed;
    EXPECT_LT(centre_error, 1.0) << seed;
  }
}

void PrintTo(const Case& c, std::ostream* os) {
  *os << (c.rerender ? "drawn " : "warped ") << c.deg << " deg, shift " << c.shift;
}
void PrintTo(const Expect& e, std::ostream* os) {
  *os << "repeatability >= " << e.repeatability << ", precision >= " << e.precision;
}

std::string CaseName(const ::testing::TestParamInfo<std::pair<Case, Expect>>& info) {
  const Case& c = info.param.first;
  return std::string(c.rerender ? "Drawn" : "Warped") + std::to_string(static_cast<int>(c.deg)) +
         "Deg" + (c.shift == cv::Point2d() ? "" : "Shift" + std::to_string(info.index));
}

INSTANTIATE_TEST_SUITE_P(
    Transforms, SurfInvarianceTest,
    ::testing::Values(std::pair{Case{30.0, {}}, Expect{0.55, 0.55}},
                      std::pair{Case{90.0, {}}, Expect{0.85, 0.9}},
                      std::pair{Case{137.0, {}}, Expect{0.55, 0.55}},
                      std::pair{Case{0.0, {3.3, -2.6}}, Expect{0.75, 0.85}},
                      std::pair{Case{0.0, {-7.5, 4.25}}, Expect{0.75, 0.85}},
                      std::pair{Case{12.0, {5.0, 1.5}}, Expect{0.7, 0.75}},
                      std::pair{Case{30.0, {}, true}, Expect{0.55, 0.55}},
                      std::pair{Case{137.0, {2.0, -3.0}, true}, Expect{0.55, 0.55}},
                      std::pair{Case{0.0, {2.5, 1.5}, true}, Expect{0.7, 0.8}}),
    CaseName);

// U-SURF: the same keypoints without orientation; its descriptors match under shifts but, not
// being rotation invariant, not under a quarter turn. SURF-128 matches under rotation too.
TEST(SurfVariantsTest, UprightAndExtended) {
  SurfOptions options;
  const cv::Ptr<cv::Feature2D> surf = SurfFeature2D::Create(options);
  options.upright = true;
  const cv::Ptr<cv::Feature2D> usurf = SurfFeature2D::Create(options);
  options.upright = false;
  options.extended = true;
  const cv::Ptr<cv::Feature2D> surf128 = SurfFeature2D::Create(options);
  const ImagePair shifted = Transformed(MakeSyntheticKeyMap(kSize, 4), 0.0, {4.5, -3.0});
  const Features fs = Describe(surf, shifted.a);
  const Features fu = Describe(usurf, shifted.a);
  ASSERT_EQ(fs.keypoints.size(), fu.keypoints.size());
  for (std::size_t i = 0; i < fs.keypoints.size(); ++i) {
    EXPECT_EQ(fs.keypoints[i].pt, fu.keypoints[i].pt);
    EXPECT_EQ(fs.keypoints[i].size, fu.keypoints[i].size);
    EXPECT_EQ(fs.keypoints[i].response, fu.keypoints[i].response);
    EXPECT_EQ(fs.keypoints[i].class_id, fu.keypoints[i].class_id);
    EXPECT_GE(fs.keypoints[i].angle, 0.0F);
    EXPECT_EQ(fu.keypoints[i].angle, -1.0F);
  }
  const MatchResult upright_shift = Match(fu, Describe(usurf, shifted.b), shifted.T_b_a);
  EXPECT_GE(upright_shift.correct, 30);
  EXPECT_GE(static_cast<double>(upright_shift.correct) / upright_shift.mutual, 0.9);

  const ImagePair turned = Transformed(MakeSyntheticKeyMap(kSize, 4), 90.0, {});
  const MatchResult upright_turn = Match(fu, Describe(usurf, turned.b), turned.T_b_a);
  EXPECT_LT(static_cast<double>(upright_turn.correct) / upright_turn.mutual, 0.3);

  const ImagePair rotated = Transformed(MakeSyntheticKeyMap(kSize, 4), 60.0, {});
  const MatchResult extended =
      Match(Describe(surf128, rotated.a), Describe(surf128, rotated.b), rotated.T_b_a);
  EXPECT_GE(extended.correct, 20);
  EXPECT_GE(static_cast<double>(extended.correct) / extended.mutual, 0.55);
  EXPECT_LT(std::abs(std::remainder(extended.fit.T_b_a.theta - rotated.T_b_a.theta, 2.0 * kPi)),
            1.0 * kPi / 180.0);
}

}  // namespace
}  // namespace gridslam::features
