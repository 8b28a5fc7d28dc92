#include "gridslam/features/surf_feature2d.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "gridslam/common/check.hpp"
#include "gridslam/common/thread_scratch.hpp"
#include "gridslam/features/fast_hessian.hpp"
#include "gridslam/features/integral_image.hpp"
#include "gridslam/features/surf_descriptor.hpp"

namespace gridslam::features {
namespace {

constexpr float kRadToDeg = static_cast<float>(180.0 / std::numbers::pi);
constexpr float kDegToRad = static_cast<float>(std::numbers::pi / 180.0);

bool Inside(const cv::KeyPoint& kp, int width, int height) {
  return kp.pt.x >= 0.0F && kp.pt.y >= 0.0F && kp.pt.x <= static_cast<float>(width - 1) &&
         kp.pt.y <= static_cast<float>(height - 1) && kp.size > 0.0F;
}

// The integral image of `img`, in a table kept per thread from call to call: a key map's table is
// a few MB, and allocated afresh every call paid the kernel's page faults for it again. Compute()
// rewrites every entry. Valid until the thread's next call.
const IntegralImage& ThreadIntegral(const cv::Mat& img) {
  struct IntegralTag {};
  IntegralImage& integral = ThreadScratch<IntegralTag, IntegralImage>();
  integral.Compute(img);
  return integral;
}

}  // namespace

cv::Ptr<cv::Feature2D> SurfFeature2D::Create(const SurfOptions& options) {
  return cv::makePtr<SurfFeature2D>(options);
}

SurfFeature2D::SurfFeature2D(const SurfOptions& options) : options_(options) {
  const Status status = options_.Validate();
  GRIDSLAM_CHECK(status.ok()) << status.error().ToString();
}

int SurfFeature2D::descriptorSize() const {
  return options_.extended ? kSurfExtendedDescriptorSize : kSurfDescriptorSize;
}

cv::String SurfFeature2D::getDefaultName() const {
  return options_.upright ? "gridslam.USURF" : "gridslam.SURF";
}

void SurfFeature2D::detectAndCompute(cv::InputArray image, cv::InputArray mask,
                                     std::vector<cv::KeyPoint>& keypoints,
                                     cv::OutputArray descriptors, bool use_provided_keypoints) {
  const cv::Mat img = image.getMat();
  GRIDSLAM_CHECK(img.empty() || img.type() == CV_8UC1)
      << "SurfFeature2D needs a CV_8UC1 image, got type " << img.type();
  if (img.empty()) {
    keypoints.clear();
    if (descriptors.needed()) {
      descriptors.release();
    }
    return;
  }
  const IntegralImage& integral = ThreadIntegral(img);
  if (use_provided_keypoints) {
    std::erase_if(keypoints,
                  [&](const cv::KeyPoint& kp) { return !Inside(kp, img.cols, img.rows); });
  } else {
    Detect(integral, mask.getMat(), keypoints);
  }
  Orient(integral, use_provided_keypoints, keypoints);
  if (descriptors.needed()) {
    Describe(integral, keypoints, descriptors);
  }
}

void SurfFeature2D::DetectThenDescribe(const cv::Mat& img, std::vector<cv::KeyPoint>& keypoints,
                                       cv::Mat& descriptors) const {
  GRIDSLAM_CHECK(img.empty() || img.type() == CV_8UC1)
      << "SurfFeature2D needs a CV_8UC1 image, got type " << img.type();
  if (img.empty()) {
    keypoints.clear();
    descriptors.release();
    return;
  }
  // detect(): detection and orientation; compute(): keypoints inside the image, descriptors.
  const IntegralImage& integral = ThreadIntegral(img);
  Detect(integral, cv::Mat(), keypoints);
  Orient(integral, false, keypoints);
  std::erase_if(keypoints, [&](const cv::KeyPoint& kp) { return !Inside(kp, img.cols, img.rows); });
  Orient(integral, true, keypoints);
  Describe(integral, keypoints, descriptors);
}

void SurfFeature2D::Detect(const IntegralImage& integral, const cv::Mat& mask,
                           std::vector<cv::KeyPoint>& keypoints) const {
  keypoints = DetectFastHessian(integral, options_);
  if (!mask.empty()) {
    GRIDSLAM_CHECK(mask.type() == CV_8UC1 && mask.rows == integral.height() &&
                   mask.cols == integral.width())
        << "bad mask";
    std::erase_if(keypoints, [&](const cv::KeyPoint& kp) {
      return mask.at<std::uint8_t>(cvRound(kp.pt.y), cvRound(kp.pt.x)) == 0;
    });
  }
  if (options_.max_features > 0 &&
      keypoints.size() > static_cast<std::size_t>(options_.max_features)) {
    keypoints.resize(static_cast<std::size_t>(options_.max_features));
  }
}

void SurfFeature2D::Orient(const IntegralImage& integral, bool provided,
                           std::vector<cv::KeyPoint>& keypoints) const {
  for (cv::KeyPoint& kp : keypoints) {
    if (options_.upright) {
      kp.angle = -1.0F;
    } else if (!provided || kp.angle < 0.0F) {
      float deg = AssignOrientation(integral, kp.pt.x, kp.pt.y, ScaleOfSize(kp.size)) * kRadToDeg;
      deg = deg < 0.0F ? deg + 360.0F : deg;
      kp.angle = deg >= 360.0F ? 0.0F : deg;
    }
  }
}

void SurfFeature2D::Describe(const IntegralImage& integral,
                             const std::vector<cv::KeyPoint>& keypoints,
                             cv::OutputArray descriptors) const {
  const int n = static_cast<int>(keypoints.size());
  descriptors.create(n, descriptorSize(), CV_32F);
  cv::Mat out = descriptors.getMat();
  for (int i = 0; i < n; ++i) {
    const cv::KeyPoint& kp = keypoints[static_cast<std::size_t>(i)];
    const float angle = options_.upright ? 0.0F : kp.angle * kDegToRad;
    ComputeSurfDescriptor(integral, kp.pt.x, kp.pt.y, ScaleOfSize(kp.size), angle,
                          options_.extended, out.ptr<float>(i));
  }
}

Result<cv::Ptr<cv::Feature2D>> CreateDetector(const std::string& name, const SurfOptions& options) {
  GRIDSLAM_RETURN_IF_ERROR(options.Validate());
  std::string key = name;
  std::transform(key.begin(), key.end(), key.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (key == "surf" || key == "usurf") {
    SurfOptions surf = options;
    surf.upright = key == "usurf";
    return SurfFeature2D::Create(surf);
  }
  if (key == "sift") {
    return cv::Ptr<cv::Feature2D>(cv::SIFT::create(options.max_features));
  }
  if (key == "orb") {
    return cv::Ptr<cv::Feature2D>(
        cv::ORB::create(options.max_features > 0 ? options.max_features : 500));
  }
  if (key == "akaze") {
    return cv::Ptr<cv::Feature2D>(cv::AKAZE::create());
  }
  return InvalidInput("unknown feature detector '" + name +
                      "' (expected surf, usurf, sift, orb or akaze)");
}

std::vector<std::string> DetectorNames() { return {"surf", "usurf", "sift", "orb", "akaze"}; }

}  // namespace gridslam::features
