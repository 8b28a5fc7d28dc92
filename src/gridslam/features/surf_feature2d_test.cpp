#include "gridslam/features/surf_feature2d.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "gridslam/features/surf_descriptor.hpp"
#include "gridslam/features/synthetic_keymap.hpp"

namespace gridslam::features {
namespace {

TEST(SurfOptionsTest, DefaultsValidAndBadValuesRejected) {
  EXPECT_TRUE(SurfOptions{}.Validate().ok());
  const auto rejected = [](auto change) {
    SurfOptions options;
    change(options);
    return !options.Validate().ok();
  };
  EXPECT_TRUE(rejected([](SurfOptions& o) { o.hessian_threshold = -1e-4; }));
  EXPECT_TRUE(rejected([](SurfOptions& o) { o.num_octaves = 0; }));
  EXPECT_TRUE(rejected([](SurfOptions& o) { o.layers_per_octave = 2; }));
  EXPECT_TRUE(rejected([](SurfOptions& o) { o.initial_step = 0; }));
  EXPECT_TRUE(rejected([](SurfOptions& o) { o.interpolation_steps = 0; }));
  EXPECT_TRUE(rejected([](SurfOptions& o) { o.max_features = -1; }));
}

TEST(SurfFeature2DTest, InterfaceAndKeypointConventions) {
  SurfOptions options;
  const cv::Ptr<cv::Feature2D> surf = SurfFeature2D::Create(options);
  EXPECT_EQ(surf->descriptorSize(), 64);
  EXPECT_EQ(surf->descriptorType(), CV_32F);
  EXPECT_EQ(surf->defaultNorm(), cv::NORM_L2);
  EXPECT_EQ(surf->getDefaultName(), "gridslam.SURF");
  options.extended = true;
  EXPECT_EQ(SurfFeature2D::Create(options)->descriptorSize(), 128);

  const cv::Mat image = MakeSyntheticKeyMap(300, 1);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  surf->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
  ASSERT_GE(keypoints.size(), 40U);
  ASSERT_EQ(descriptors.rows, static_cast<int>(keypoints.size()));
  ASSERT_EQ(descriptors.cols, 64);
  ASSERT_EQ(descriptors.type(), CV_32F);
  int positive = 0;
  for (int i = 0; i < descriptors.rows; ++i) {
    const cv::KeyPoint& kp = keypoints[static_cast<std::size_t>(i)];
    EXPECT_NEAR(cv::norm(descriptors.row(i)), 1.0, 1e-5);
    EXPECT_TRUE(kp.class_id == 1 || kp.class_id == -1);
    positive += kp.class_id == 1 ? 1 : 0;
    EXPECT_GE(kp.angle, 0.0F);
    EXPECT_LT(kp.angle, 360.0F);
    EXPECT_GE(kp.size, 9.0F);
    EXPECT_TRUE(kp.octave >= 0 && kp.octave < options.num_octaves);
    EXPECT_GE(kp.response, options.hessian_threshold);
    EXPECT_TRUE(kp.pt.x >= 0 && kp.pt.y >= 0 && kp.pt.x <= 299 && kp.pt.y <= 299);
  }
  // A distance image has maxima (room centres, Laplacian −1) and minima (obstacle ends, +1).
  EXPECT_GT(positive, 0);
  EXPECT_LT(positive, descriptors.rows);
}

TEST(SurfFeature2DTest, DetectThenComputeEqualsDetectAndCompute) {
  const cv::Ptr<cv::Feature2D> surf = SurfFeature2D::Create(SurfOptions{});
  const cv::Mat image = MakeSyntheticKeyMap(260, 2);
  std::vector<cv::KeyPoint> together;
  cv::Mat d_together;
  surf->detectAndCompute(image, cv::noArray(), together, d_together);
  std::vector<cv::KeyPoint> separate;
  surf->detect(image, separate);
  cv::Mat d_separate;
  surf->compute(image, separate, d_separate);
  ASSERT_EQ(separate.size(), together.size());
  for (std::size_t i = 0; i < separate.size(); ++i) {
    EXPECT_EQ(separate[i].pt, together[i].pt);
    EXPECT_EQ(separate[i].angle, together[i].angle);
  }
  EXPECT_EQ(cv::norm(d_separate, d_together, cv::NORM_INF), 0.0);

  // Without angles, compute() assigns them; keypoints outside the image are dropped.
  std::vector<cv::KeyPoint> bare = separate;
  for (cv::KeyPoint& kp : bare) {
    kp.angle = -1.0F;
  }
  bare.emplace_back(cv::Point2f(-3.0F, 10.0F), 20.0F);
  bare.emplace_back(cv::Point2f(10.0F, 260.0F), 20.0F);
  cv::Mat d_bare;
  surf->compute(image, bare, d_bare);
  ASSERT_EQ(bare.size(), separate.size());
  EXPECT_EQ(cv::norm(d_bare, d_together, cv::NORM_INF), 0.0);

  // Descriptors on another image (the binary obstacle image, docs/design.md §1.4) at the same
  // keypoints.
  const cv::Mat obstacles = RenderObstacleImage(MakeSyntheticWalls(260, 2), 260);
  std::vector<cv::KeyPoint> on_grid = separate;
  cv::Mat d_grid;
  surf->compute(obstacles, on_grid, d_grid);
  EXPECT_EQ(d_grid.rows, static_cast<int>(separate.size()));
  EXPECT_GT(cv::norm(d_grid, d_together, cv::NORM_INF), 0.0);
}

TEST(SurfFeature2DTest, MaskMaxFeaturesAndEmptyImage) {
  const cv::Mat image = MakeSyntheticKeyMap(300, 3);
  SurfOptions options;
  std::vector<cv::KeyPoint> all;
  SurfFeature2D::Create(options)->detect(image, all);
  cv::Mat mask = cv::Mat::zeros(image.size(), CV_8UC1);
  mask(cv::Rect(0, 0, 150, 300)).setTo(255);
  std::vector<cv::KeyPoint> left;
  SurfFeature2D::Create(options)->detect(image, left, mask);
  EXPECT_GT(left.size(), 0U);
  EXPECT_LT(left.size(), all.size());
  for (const cv::KeyPoint& kp : left) {
    EXPECT_LT(kp.pt.x, 150.0F);
  }
  options.max_features = 10;
  std::vector<cv::KeyPoint> strongest;
  SurfFeature2D::Create(options)->detect(image, strongest);
  ASSERT_EQ(strongest.size(), 10U);
  for (std::size_t i = 0; i < strongest.size(); ++i) {
    EXPECT_EQ(strongest[i].response, all[i].response);
  }
  std::vector<cv::KeyPoint> none = all;
  cv::Mat descriptors;
  SurfFeature2D::Create(options)->detectAndCompute(cv::Mat(), cv::noArray(), none, descriptors);
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(descriptors.empty());
}

TEST(CreateDetectorTest, EveryNameWorksOnAKeyMapImage) {
  const cv::Mat image = MakeSyntheticKeyMap(300, 1);
  for (const std::string& name : DetectorNames()) {
    const Result<cv::Ptr<cv::Feature2D>> detector = CreateDetector(name, SurfOptions{});
    ASSERT_TRUE(detector.ok()) << name;
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    detector.value()->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
    EXPECT_GE(keypoints.size(), 10U) << name;
    EXPECT_EQ(descriptors.rows, static_cast<int>(keypoints.size())) << name;
  }
  const Result<cv::Ptr<cv::Feature2D>> upright = CreateDetector("USURF", SurfOptions{});
  ASSERT_TRUE(upright.ok());
  EXPECT_EQ(upright.value()->getDefaultName(), "gridslam.USURF");
  // max_features caps SIFT and ORB (ORB only roughly: it splits the number over its levels).
  SurfOptions capped;
  capped.max_features = 25;
  for (const std::string name : {"sift", "orb"}) {
    std::vector<cv::KeyPoint> all;
    CreateDetector(name, SurfOptions{}).value()->detect(image, all);
    std::vector<cv::KeyPoint> keypoints;
    CreateDetector(name, capped).value()->detect(image, keypoints);
    EXPECT_LT(keypoints.size(), all.size()) << name;
    EXPECT_LE(keypoints.size(), 50U) << name;
  }

  const Result<cv::Ptr<cv::Feature2D>> unknown = CreateDetector("brisk", SurfOptions{});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ErrorCode::kInvalidInput);
  SurfOptions bad;
  bad.num_octaves = 0;
  EXPECT_FALSE(CreateDetector("surf", bad).ok());
}

}  // namespace
}  // namespace gridslam::features
