#include "gridslam/matching/descriptor_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "gridslam/matching/descriptor_distances.hpp"
#include "gridslam/matching/internal/synthetic.hpp"

namespace gridslam::matching {
namespace {

// A set whose descriptors are the given rows (2-D float descriptors are easy to reason about).
FeatureSet Set(const std::vector<std::vector<float>>& rows, std::vector<int> signs = {}) {
  FeatureSet s;
  const int dim = static_cast<int>(rows.front().size());
  s.descriptors = cv::Mat(static_cast<int>(rows.size()), dim, CV_32F);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (int c = 0; c < dim; ++c) {
      s.descriptors.at<float>(static_cast<int>(r), c) = rows[r][static_cast<std::size_t>(c)];
    }
    s.points.emplace_back(static_cast<double>(r), 0.0);
  }
  s.laplacian_sign = std::move(signs);
  return s;
}

bool Has(const std::vector<Match>& m, int ia, int ib) {
  return std::any_of(m.begin(), m.end(),
                     [&](const Match& x) { return x.index_a == ia && x.index_b == ib; });
}

TEST(MatchDescriptors, MutualNearestNeighbours) {
  // a0 -> b0 mutual; a1 -> b0 too (not mutual: b0 prefers a0); a2 -> b2 mutual.
  const FeatureSet a = Set({{0.0F, 0.0F}, {0.3F, 0.0F}, {5.0F, 5.0F}});
  const FeatureSet b = Set({{0.1F, 0.0F}, {2.0F, 0.0F}, {5.0F, 5.2F}});
  DescriptorMatchOptions options;
  options.max_ratio = 1.0;
  const std::vector<Match> m = MatchDescriptors(a, b, options);
  ASSERT_EQ(m.size(), 2U);
  EXPECT_TRUE(Has(m, 0, 0));
  EXPECT_TRUE(Has(m, 2, 2));
  EXPECT_NEAR(m[0].distance, 0.1F, 1e-6F);
  EXPECT_NEAR(m[1].distance, 0.2F, 1e-5F);
  // Without cross-check a1 keeps its nearest neighbour b0.
  options.cross_check_k = 0;
  EXPECT_TRUE(Has(MatchDescriptors(a, b, options), 1, 0));
  // The authors' relaxed cross-check: a1's nearest b0 has a1 among its 2 nearest, so a1 is
  // matched too (several a features may share one b feature).
  options.cross_check_k = 2;
  const std::vector<Match> relaxed = MatchDescriptors(a, b, options);
  EXPECT_TRUE(Has(relaxed, 0, 0));
  EXPECT_TRUE(Has(relaxed, 1, 0));
}

TEST(MatchDescriptors, RatioTestRejectsAmbiguousMatches) {
  // a0 is nearly equidistant to b0 and b1; a1 has a clear nearest neighbour b2.
  const FeatureSet a = Set({{0.0F, 0.0F}, {10.0F, 0.0F}});
  const FeatureSet b = Set({{1.0F, 0.0F}, {-1.05F, 0.0F}, {10.2F, 0.0F}});
  DescriptorMatchOptions options;
  options.max_ratio = 1.0;
  EXPECT_TRUE(Has(MatchDescriptors(a, b, options), 0, 0));
  options.max_ratio = 0.8;
  const std::vector<Match> m = MatchDescriptors(a, b, options);
  EXPECT_FALSE(Has(m, 0, 0));
  EXPECT_TRUE(Has(m, 1, 2));
  // The column's ratio counts too: b0 is close to a0 and to a new a2.
  const FeatureSet a3 = Set({{0.0F, 0.0F}, {10.0F, 0.0F}, {1.0F, 1.05F}});
  const FeatureSet b1 = Set({{1.0F, 0.0F}, {10.2F, 0.0F}});
  EXPECT_FALSE(Has(MatchDescriptors(a3, b1, options), 0, 0));
}

TEST(MatchDescriptors, LaplacianSignGatesCandidates) {
  const FeatureSet a = Set({{0.0F, 0.0F}}, {+1});
  const FeatureSet b = Set({{0.1F, 0.0F}, {1.0F, 0.0F}}, {-1, +1});
  DescriptorMatchOptions options;
  options.max_ratio = 1.0;
  std::vector<Match> m = MatchDescriptors(a, b, options);
  ASSERT_EQ(m.size(), 1U);
  EXPECT_EQ(m[0].index_b, 1);  // the nearer b0 has the other sign
  options.use_laplacian_sign = false;
  m = MatchDescriptors(a, b, options);
  ASSERT_EQ(m.size(), 1U);
  EXPECT_EQ(m[0].index_b, 0);
  // With the gate, the ratio test only sees same-sign candidates: b1 is then unambiguous.
  options.use_laplacian_sign = true;
  options.max_ratio = 0.5;
  EXPECT_EQ(MatchDescriptors(a, b, options).size(), 1U);
  // Only opposite signs: nothing to match.
  const FeatureSet c = Set({{0.1F, 0.0F}}, {-1});
  EXPECT_TRUE(MatchDescriptors(a, c, options).empty());
}

TEST(MatchDescriptors, ScaleGate) {
  FeatureSet a = Set({{0.0F, 0.0F}});
  FeatureSet b = Set({{0.1F, 0.0F}, {1.0F, 0.0F}});
  a.scales = {0.5};
  b.scales = {2.0, 0.6};
  DescriptorMatchOptions options;
  options.max_ratio = 1.0;
  EXPECT_EQ(MatchDescriptors(a, b, options)[0].index_b, 0);
  options.max_scale_ratio = 1.5;
  EXPECT_EQ(MatchDescriptors(a, b, options)[0].index_b, 1);
}

TEST(MatchDescriptors, BinaryDescriptorsUseHamming) {
  FeatureSet a;
  FeatureSet b;
  a.descriptors = cv::Mat::zeros(2, 32, CV_8U);
  b.descriptors = cv::Mat::zeros(2, 32, CV_8U);
  a.descriptors.row(1).setTo(0xFF);
  b.descriptors.row(0).setTo(0xFF);
  b.descriptors.at<std::uint8_t>(0, 31) = 0x0F;  // 4 bits from a1
  b.descriptors.at<std::uint8_t>(1, 3) = 0x03;   // 2 bits from a0
  a.points = {{0, 0}, {1, 0}};
  b.points = {{0, 0}, {1, 0}};
  const std::vector<Match> m = MatchDescriptors(a, b, DescriptorMatchOptions{});
  ASSERT_EQ(m.size(), 2U);
  EXPECT_TRUE(Has(m, 0, 1));
  EXPECT_TRUE(Has(m, 1, 0));
  EXPECT_EQ(m[0].distance, 2.0F);
  EXPECT_EQ(m[1].distance, 4.0F);
}

TEST(MatchDescriptors, FindsTheTrueMatchesOfSyntheticSetsSymmetrically) {
  const Pose2 T_a_b(1.0, -2.0, 0.4);
  const auto pair = internal::MakeFeaturePair(T_a_b, 200, 180, 60, 0.02, 5);
  const std::vector<Match> m = MatchDescriptors(pair.a, pair.b, DescriptorMatchOptions{});
  int correct = 0;
  for (const Match& t : pair.truth) {
    correct += Has(m, t.index_a, t.index_b) ? 1 : 0;
  }
  EXPECT_GE(correct, 58);
  EXPECT_LE(static_cast<int>(m.size()) - correct, 10);
  // Swapping the sets swaps the matches.
  const std::vector<Match> swapped = MatchDescriptors(pair.b, pair.a, DescriptorMatchOptions{});
  ASSERT_EQ(swapped.size(), m.size());
  for (const Match& x : swapped) {
    EXPECT_TRUE(Has(m, x.index_b, x.index_a));
  }
}

TEST(MatchDescriptors, EmptySetsGiveNoMatches) {
  const FeatureSet a = Set({{0.0F, 0.0F}});
  EXPECT_TRUE(MatchDescriptors(a, FeatureSet{}, {}).empty());
  EXPECT_TRUE(MatchDescriptors(FeatureSet{}, a, {}).empty());
  EXPECT_TRUE(MatchDescriptors(FeatureSet{}, FeatureSet{}, {}).empty());
}

// The matcher's definition on the whole distance matrix: gated pairs infinite; each row's and
// column's `keep` nearest finite entries (ties to the lower index); the cross-check, ratio and
// distance tests on them.
std::vector<Match> ReferenceMatches(const FeatureSet& a, const FeatureSet& b,
                                    const DescriptorMatchOptions& options) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  RowMajorMatrixXf d = SquaredEuclideanDistances(a.descriptors, b.descriptors);
  for (int i = 0; i < a.size(); ++i) {
    for (int j = 0; j < b.size(); ++j) {
      const auto ui = static_cast<std::size_t>(i);
      const auto uj = static_cast<std::size_t>(j);
      if ((options.use_laplacian_sign &&
           (a.laplacian_sign[ui] > 0) != (b.laplacian_sign[uj] > 0)) ||
          (options.max_scale_ratio > 0.0 &&
           (a.scales[ui] > options.max_scale_ratio * b.scales[uj] ||
            b.scales[uj] > options.max_scale_ratio * a.scales[ui]))) {
        d(i, j) = kInf;
      }
    }
  }
  const int k = std::max(options.cross_check_k, 1);
  const auto nearest = [&](int n, const auto& at) {  // finite entries, nearest first
    std::vector<int> order;
    for (int x = 0; x < n; ++x) {
      if (at(x) < kInf) {
        order.push_back(x);
      }
    }
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return at(x) < at(y); });
    order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(k) + 1));
    return order;
  };
  const auto second_best = [](const std::vector<int>& list, int excluded, const auto& at) {
    for (const int x : list) {
      if (x != excluded) {
        return at(x);
      }
    }
    return kInf;
  };
  const double ratio = options.max_ratio * options.max_ratio;
  std::vector<Match> matches;
  for (int i = 0; i < a.size(); ++i) {
    const auto in_row = [&](int j) { return d(i, j); };
    const std::vector<int> row = nearest(b.size(), in_row);
    int chosen = -1;
    const int candidates = options.cross_check_k == 0 ? 1 : k;
    for (int r = 0; r < std::min<int>(candidates, static_cast<int>(row.size())) && chosen < 0;
         ++r) {
      const int j = row[static_cast<std::size_t>(r)];
      const std::vector<int> col = nearest(a.size(), [&](int x) { return d(x, j); });
      if (options.cross_check_k == 0 ||
          std::find(col.begin(), col.begin() + std::min<int>(k, static_cast<int>(col.size())), i) !=
              col.begin() + std::min<int>(k, static_cast<int>(col.size()))) {
        chosen = j;
      }
    }
    if (chosen < 0) {
      continue;
    }
    const double dist = d(i, chosen);
    const auto in_col = [&](int x) { return d(x, chosen); };
    if (options.max_ratio < 1.0 &&
        (!(dist < ratio * second_best(row, chosen, in_row)) ||
         (options.cross_check_k > 0 &&
          !(dist < ratio * second_best(nearest(a.size(), in_col), i, in_col))))) {
      continue;
    }
    matches.push_back({i, chosen, static_cast<float>(std::sqrt(dist))});
  }
  return matches;
}

// Over random sets with many equal distances (descriptors of small integers), with and without
// the gates, for several cross-checks and ratios: the matcher's matches are the definition's,
// to the last bit of their distances.
TEST(MatchDescriptors, AgreeWithTheDefinitionOnTheWholeDistanceMatrix) {
  std::mt19937 random(17);
  std::uniform_int_distribution<int> value(0, 2);
  std::uniform_real_distribution<double> scale(0.5, 2.0);
  const auto random_set = [&](int n) {
    std::vector<std::vector<float>> rows(static_cast<std::size_t>(n), std::vector<float>(4));
    std::vector<int> signs;
    for (auto& r : rows) {
      for (float& x : r) {
        x = static_cast<float>(value(random));
      }
      signs.push_back(value(random) == 0 ? -1 : 1);
    }
    FeatureSet s = Set(rows, signs);
    for (int k = 0; k < n; ++k) {
      s.scales.push_back(scale(random));
    }
    return s;
  };
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const FeatureSet a = random_set(40 + trial);
    const FeatureSet b = random_set(50 - trial);
    for (const int cross_check_k : {0, 1, 3}) {
      for (const double max_ratio : {1.0, 0.9}) {
        for (const bool gates : {false, true}) {
          DescriptorMatchOptions options;
          options.cross_check_k = cross_check_k;
          options.max_ratio = max_ratio;
          options.use_laplacian_sign = gates;
          options.max_scale_ratio = gates ? 1.5 : 0.0;
          const std::vector<Match> expected = ReferenceMatches(a, b, options);
          const std::vector<Match> m = MatchDescriptors(a, b, options);
          ASSERT_EQ(m.size(), expected.size()) << trial << " " << cross_check_k;
          for (std::size_t x = 0; x < m.size(); ++x) {
            EXPECT_EQ(m[x].index_a, expected[x].index_a);
            EXPECT_EQ(m[x].index_b, expected[x].index_b);
            EXPECT_EQ(m[x].distance, expected[x].distance);
          }
          compared += static_cast<int>(m.size());
        }
      }
    }
  }
  EXPECT_GT(compared, 500);
}

TEST(FeatureSetError, ReportsInconsistentSets) {
  FeatureSet s = Set({{0.0F, 0.0F}, {1.0F, 1.0F}});
  EXPECT_TRUE(FeatureSetError(s).empty());
  s.laplacian_sign = {1};
  EXPECT_FALSE(FeatureSetError(s).empty());
  s.laplacian_sign.clear();
  s.points.pop_back();
  EXPECT_FALSE(FeatureSetError(s).empty());
  s = Set({{0.0F, 0.0F}});
  s.descriptors.convertTo(s.descriptors, CV_64F);
  EXPECT_FALSE(FeatureSetError(s).empty());
}

}  // namespace
}  // namespace gridslam::matching
