#include "gridslam/matching/descriptor_distances.hpp"

#include <bit>
#include <cstdint>
#include <cstring>

#include "gridslam/common/check.hpp"

namespace gridslam::matching {

RowMajorMatrixXf SquaredEuclideanDistances(const cv::Mat& a, const cv::Mat& b) {
  GRIDSLAM_CHECK(a.type() == CV_32F && b.type() == CV_32F && a.cols == b.cols)
      << "float descriptors of one length expected";
  const cv::Mat ac = a.isContinuous() ? a : a.clone();
  const cv::Mat bc = b.isContinuous() ? b : b.clone();
  const Eigen::Map<const RowMajorMatrixXf> ma(ac.ptr<float>(), ac.rows, ac.cols);
  const Eigen::Map<const RowMajorMatrixXf> mb(bc.ptr<float>(), bc.rows, bc.cols);
  RowMajorMatrixXf d = -2.0F * (ma * mb.transpose());
  const Eigen::VectorXf na = ma.rowwise().squaredNorm();
  const Eigen::RowVectorXf nb = mb.rowwise().squaredNorm().transpose();
  // |a|^2 + |b|^2 - 2 a.b, clamped at 0, in one pass in place: the additions in the order of
  // d.colwise() += na, d.rowwise() += nb, then d.cwiseMax(0) (a new matrix) did them.
  for (Eigen::Index i = 0; i < d.rows(); ++i) {
    float* row = d.row(i).data();
    const float norm_a = na(i);
    for (Eigen::Index j = 0; j < d.cols(); ++j) {
      const float v = (row[j] + norm_a) + nb(j);
      row[j] = v < 0.0F ? 0.0F : v;  // as cwiseMax(0): std::max(v, 0)
    }
  }
  return d;
}

// On x86-64 with GCC a clone using the POPCNT instruction is chosen at load time (the baseline
// ISA has none).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("popcnt", "default")))
#endif
RowMajorMatrixXf
HammingDistances(const cv::Mat& a, const cv::Mat& b) {
  GRIDSLAM_CHECK(a.type() == CV_8U && b.type() == CV_8U && a.cols == b.cols)
      << "binary descriptors of one length expected";
  const int bytes = a.cols;
  const int words = bytes / 8;
  RowMajorMatrixXf d(a.rows, b.rows);
  for (int i = 0; i < a.rows; ++i) {
    const std::uint8_t* pa = a.ptr<std::uint8_t>(i);
    for (int j = 0; j < b.rows; ++j) {
      const std::uint8_t* pb = b.ptr<std::uint8_t>(j);
      int bits = 0;
      for (int w = 0; w < words; ++w) {
        std::uint64_t x = 0;
        std::uint64_t y = 0;
        std::memcpy(&x, pa + 8 * w, 8);
        std::memcpy(&y, pb + 8 * w, 8);
        bits += std::popcount(x ^ y);
      }
      for (int c = 8 * words; c < bytes; ++c) {
        bits += std::popcount(static_cast<unsigned>(pa[c] ^ pb[c]));
      }
      d(i, j) = static_cast<float>(bits);
    }
  }
  return d;
}

}  // namespace gridslam::matching
