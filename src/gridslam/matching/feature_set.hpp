// Input of the key-map aligner (docs/design.md §1.5, docs/method.md §1.5.2–1.5.3): the features of
// one key map, already converted to metres in the key map's own frame (the window centre, yaw 0,
// docs/design.md §1.3), and a putative correspondence between two such sets. The type is
// independent of the detector: SURF (float descriptors, sign of the Laplacian), SIFT, or binary
// ORB/AKAZE descriptors (CV_8U rows compared by Hamming distance) all fill the same struct.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace gridslam::matching {

/// The features of one key map.
struct FeatureSet {
  /// Keypoint positions in the key map's own frame [m].
  std::vector<Eigen::Vector2d> points;
  /// One descriptor per point, row i for points[i]: CV_32F (Euclidean distance) or CV_8U
  /// (binary, Hamming distance). May be empty only when `points` is empty.
  cv::Mat descriptors;
  /// Sign of the Laplacian (+1 / -1) per point (SURF, Bay et al. 2008 §4.1); empty if unknown.
  std::vector<int> laplacian_sign;
  /// Keypoint scale per point [m] (e.g. SURF's 1.2·L/9 · resolution); empty if unknown.
  std::vector<double> scales;
  /// Keypoint orientation per point in the key map's frame [rad], counter-clockwise from +x,
  /// so that under p_a = T_a_b * p_b an orientation maps as angle_a = angle_b + theta.
  /// Leave empty for upright (U-SURF) features: a constant angle would veto every rotation.
  std::vector<double> angles;

  [[nodiscard]] int size() const { return static_cast<int>(points.size()); }
  [[nodiscard]] bool empty() const { return points.empty(); }
};

/// Why a FeatureSet is malformed (descriptor rows, optional vectors of the wrong length, an
/// unsupported descriptor type); empty if it is consistent.
std::string FeatureSetError(const FeatureSet& features);

/// A putative correspondence: feature `index_a` of set a and feature `index_b` of set b.
struct Match {
  int index_a = 0;
  int index_b = 0;
  float distance = 0.0F;  ///< Descriptor distance (Euclidean or Hamming).
};

}  // namespace gridslam::matching
