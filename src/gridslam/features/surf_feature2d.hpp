// SURF (Bay et al. 2008) as a cv::Feature2D, so that the key-map description pipeline
// (docs/design.md §1.4) can swap in OpenCV's SIFT, ORB or AKAZE through the same interface
// (CreateDetector). detect() runs the Fast-Hessian detector (fast_hessian.hpp) and, unless upright,
// assigns each keypoint's orientation; compute() describes given keypoints (surf_descriptor.hpp),
// using a keypoint's angle when it is >= 0 and assigning one otherwise. Keypoints follow
// fast_hessian.hpp: size = filter size L (s = 1.2·L/9), class_id = sign of the Laplacian (±1),
// angle in degrees [0, 360) clockwise in the image (−1 for U-SURF). Descriptors are CV_32F rows
// of 64 (or, extended, 128) unit-norm values, compared with NORM_L2. Input images are CV_8UC1;
// a mask (CV_8UC1, image size) keeps keypoints whose rounded position is non-zero. Keypoints
// given to compute() that lie outside the image are removed. Objects are immutable after
// creation, so one may be shared by threads.
#pragma once

#include <string>
#include <vector>

#include <opencv2/features2d.hpp>

#include "gridslam/common/result.hpp"
#include "gridslam/features/integral_image.hpp"
#include "gridslam/features/surf_options.hpp"

namespace gridslam::features {

class SurfFeature2D : public cv::Feature2D {
 public:
  /// A SURF detector/descriptor. Contract: options.Validate() is ok.
  static cv::Ptr<cv::Feature2D> Create(const SurfOptions& options);
  explicit SurfFeature2D(const SurfOptions& options);

  // NOLINTBEGIN(readability-identifier-naming): OpenCV's virtual interface.
  void detectAndCompute(cv::InputArray image, cv::InputArray mask,
                        std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                        bool use_provided_keypoints) override;
  [[nodiscard]] int descriptorSize() const override;
  [[nodiscard]] int descriptorType() const override { return CV_32F; }
  [[nodiscard]] int defaultNorm() const override { return cv::NORM_L2; }
  [[nodiscard]] cv::String getDefaultName() const override;
  [[nodiscard]] bool empty() const override { return false; }
  // NOLINTEND(readability-identifier-naming)

  [[nodiscard]] const SurfOptions& options() const { return options_; }

  /// detect(image, keypoints) followed by compute(image, keypoints, descriptors) on the same
  /// image, with one integral image instead of two (the same keypoints and descriptors).
  void DetectThenDescribe(const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints,
                          cv::Mat& descriptors) const;

 private:
  void Detect(const IntegralImage& integral, const cv::Mat& mask,
              std::vector<cv::KeyPoint>& keypoints) const;
  /// Orientation of every keypoint (`provided`: only of those without one).
  void Orient(const IntegralImage& integral, bool provided,
              std::vector<cv::KeyPoint>& keypoints) const;
  void Describe(const IntegralImage& integral, const std::vector<cv::KeyPoint>& keypoints,
                cv::OutputArray descriptors) const;

  SurfOptions options_;
};

/// A feature detector/descriptor by name: "surf" (the options with upright = false), "usurf"
/// (upright = true), and OpenCV's "sift", "orb" and "akaze" with their defaults, except that
/// options.max_features > 0 caps SIFT's and (roughly) ORB's feature count; the other options
/// are SURF's only. Case-insensitive; an unknown
/// name or invalid options give an InvalidInput error.
[[nodiscard]] Result<cv::Ptr<cv::Feature2D>> CreateDetector(const std::string& name,
                                                            const SurfOptions& options);

/// The names CreateDetector accepts.
[[nodiscard]] std::vector<std::string> DetectorNames();

}  // namespace gridslam::features
