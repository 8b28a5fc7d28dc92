// Distance matrices between two sets of descriptors (rows of a cv::Mat), the brute-force core of
// descriptor association (descriptor_matcher.hpp). Float descriptors: squared Euclidean distances
// computed as |a|² + |b|² − 2 a·b, one matrix product, clamped at 0. Binary descriptors: Hamming
// distances, 64 bits per popcount. (The appearance index's newest block stays with
// cv::batchDistance: measured against this GEMM on fr079, OpenCV's dispatched, parallel kernel was
// faster; docs/speed.md, round 17.)
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace gridslam::matching {

using RowMajorMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// d(i, j) = squared Euclidean distance between row i of `a` and row j of `b`.
/// Contract: both CV_32F with the same number of columns.
[[nodiscard]] RowMajorMatrixXf SquaredEuclideanDistances(const cv::Mat& a, const cv::Mat& b);

/// d(i, j) = number of differing bits between row i of `a` and row j of `b`.
/// Contract: both CV_8U with the same number of columns.
[[nodiscard]] RowMajorMatrixXf HammingDistances(const cv::Mat& a, const cv::Mat& b);

}  // namespace gridslam::matching
