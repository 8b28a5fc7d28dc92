#include "gridslam/matching/descriptor_matcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "gridslam/common/check.hpp"
#include "gridslam/matching/descriptor_distances.hpp"

namespace gridslam::matching {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kMaxK = 17;  // cross_check_k <= 16, plus one for the ratio test

// The `k` smallest entries (indices, ascending distance, ties to the lower index) of a row or
// column; missing entries are -1.
struct TopK {
  std::array<int, kMaxK> index{};
  std::array<float, kMaxK> value{};
  void Reset(int k) {
    std::fill_n(index.begin(), k, -1);
    std::fill_n(value.begin(), k, kInf);
  }
  void Offer(int k, int idx, float v) {
    if (!(v < value[static_cast<std::size_t>(k - 1)])) {
      return;
    }
    int pos = k - 1;
    while (pos > 0 && v < value[static_cast<std::size_t>(pos - 1)]) {
      value[static_cast<std::size_t>(pos)] = value[static_cast<std::size_t>(pos - 1)];
      index[static_cast<std::size_t>(pos)] = index[static_cast<std::size_t>(pos - 1)];
      --pos;
    }
    value[static_cast<std::size_t>(pos)] = v;
    index[static_cast<std::size_t>(pos)] = idx;
  }
  // The largest value kept (infinite while fewer than k are): what an offer must beat.
  [[nodiscard]] float Worst(int k) const { return value[static_cast<std::size_t>(k - 1)]; }
  // Smallest value among the entries other than `idx`.
  [[nodiscard]] float BestExcluding(int idx) const { return index[0] == idx ? value[1] : value[0]; }
  [[nodiscard]] bool Contains(int k, int idx) const {
    return std::find(index.begin(), index.begin() + k, idx) != index.begin() + k;
  }
};

// The gates of DescriptorMatchOptions: pairs that cannot match (Laplacian signs differ, scales
// more than max_scale_ratio apart), with each column's side of the tests computed once.
class Gates {
 public:
  Gates(const FeatureSet& a, const FeatureSet& b, const DescriptorMatchOptions& options)
      : a_(a),
        ratio_(options.max_scale_ratio),
        sign_(options.use_laplacian_sign && !a.laplacian_sign.empty() && !b.laplacian_sign.empty()),
        scale_(options.max_scale_ratio > 0.0 && !a.scales.empty() && !b.scales.empty()) {
    if (sign_) {
      for (const int sign : b.laplacian_sign) {
        positive_b_.push_back(sign > 0);
      }
    }
    if (scale_) {
      scale_b_ = b.scales;
      for (const double scale : b.scales) {
        scaled_b_.push_back(ratio_ * scale);
      }
    }
  }
  // The row the next Blocks() calls test.
  void SetRow(int i) {
    const auto ui = static_cast<std::size_t>(i);
    if (sign_) {
      positive_a_ = a_.laplacian_sign[ui] > 0;
    }
    if (scale_) {
      scale_a_ = a_.scales[ui];
      scaled_a_ = ratio_ * a_.scales[ui];
    }
  }
  [[nodiscard]] bool Blocks(int j) const {
    const auto uj = static_cast<std::size_t>(j);
    return (sign_ && positive_a_ != static_cast<bool>(positive_b_[uj])) ||
           (scale_ && (scale_a_ > scaled_b_[uj] || scale_b_[uj] > scaled_a_));
  }

 private:
  const FeatureSet& a_;
  double ratio_;
  bool sign_;
  bool scale_;
  std::vector<unsigned char> positive_b_;
  std::vector<double> scale_b_;
  std::vector<double> scaled_b_;  ///< max_scale_ratio * b's scale
  bool positive_a_ = false;
  double scale_a_ = 0.0;
  double scaled_a_ = 0.0;
};

}  // namespace

std::vector<Match> MatchDescriptors(const FeatureSet& a, const FeatureSet& b,
                                    const DescriptorMatchOptions& options) {
  GRIDSLAM_CHECK(FeatureSetError(a).empty()) << "feature set a: " << FeatureSetError(a);
  GRIDSLAM_CHECK(FeatureSetError(b).empty()) << "feature set b: " << FeatureSetError(b);
  if (a.empty() || b.empty()) {
    return {};
  }
  GRIDSLAM_CHECK(a.descriptors.type() == b.descriptors.type() &&
                 a.descriptors.cols == b.descriptors.cols)
      << "descriptor types or lengths differ";
  const bool binary = a.descriptors.depth() == CV_8U;
  const RowMajorMatrixXf d = binary ? HammingDistances(a.descriptors, b.descriptors)
                                    : SquaredEuclideanDistances(a.descriptors, b.descriptors);
  const int na = a.size();
  const int nb = b.size();

  // The `keep` nearest of every row and column among the pairs the gates let through (a gated
  // pair is never offered: no list takes it, as an infinite distance would not be taken).
  const int k = std::max(options.cross_check_k, 1);
  const int keep = std::min(k + 1, kMaxK);  // one more for the ratio test
  std::vector<TopK> rows(static_cast<std::size_t>(na));
  std::vector<TopK> cols(static_cast<std::size_t>(nb));
  for (auto& c : cols) {
    c.Reset(keep);
  }
  // What an offer must beat in each column, side by side: most pairs are turned away by two
  // comparisons, without reading the columns' lists.
  std::vector<float> col_worst(static_cast<std::size_t>(nb), kInf);
  Gates gates(a, b, options);
  for (int i = 0; i < na; ++i) {
    TopK& row = rows[static_cast<std::size_t>(i)];
    row.Reset(keep);
    gates.SetRow(i);
    const float* distances = d.data() + static_cast<std::ptrdiff_t>(i) * nb;
    for (int j = 0; j < nb; ++j) {
      const float v = distances[j];
      const auto uj = static_cast<std::size_t>(j);
      if ((!(v < row.Worst(keep)) && !(v < col_worst[uj])) || gates.Blocks(j)) {
        continue;
      }
      row.Offer(keep, j, v);
      cols[uj].Offer(keep, i, v);
      col_worst[uj] = cols[uj].Worst(keep);
    }
  }

  // Squared Euclidean distances compare with the squared thresholds.
  const double ratio = binary ? options.max_ratio : options.max_ratio * options.max_ratio;
  const double max_distance =
      binary ? options.max_descriptor_distance
             : options.max_descriptor_distance * options.max_descriptor_distance;
  std::vector<Match> matches;
  for (int i = 0; i < na; ++i) {
    const TopK& row = rows[static_cast<std::size_t>(i)];
    int chosen = -1;
    const int candidates = options.cross_check_k == 0 ? 1 : k;
    for (int r = 0; r < candidates && chosen < 0; ++r) {
      const int j = row.index[static_cast<std::size_t>(r)];
      if (j < 0 || row.value[static_cast<std::size_t>(r)] == kInf) {
        break;
      }
      if (options.cross_check_k == 0 || cols[static_cast<std::size_t>(j)].Contains(k, i)) {
        chosen = j;
      }
    }
    if (chosen < 0) {
      continue;
    }
    const double dist = d(i, chosen);
    if (options.max_ratio < 1.0) {
      if (!(dist < ratio * row.BestExcluding(chosen))) {
        continue;
      }
      if (options.cross_check_k > 0 &&
          !(dist < ratio * cols[static_cast<std::size_t>(chosen)].BestExcluding(i))) {
        continue;
      }
    }
    if (options.max_descriptor_distance > 0.0 && dist > max_distance) {
      continue;
    }
    matches.push_back(
        {i, chosen, binary ? static_cast<float>(dist) : static_cast<float>(std::sqrt(dist))});
  }
  return matches;
}

}  // namespace gridslam::matching
