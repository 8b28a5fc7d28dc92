#include "gridslam/loop_closure/appearance_index.hpp"

#include <gtest/gtest.h>

#include <random>

namespace gridslam::loop_closure {
namespace {

cv::Mat RandomDescriptors(std::mt19937& rng, int rows) {
  std::normal_distribution<float> noise(0.0F, 1.0F);
  cv::Mat d(rows, 64, CV_32F);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < 64; ++c) {
      d.at<float>(r, c) = noise(rng);
    }
  }
  return d;
}

TEST(AppearanceIndex, VotesForTheKeyMapThatLooksAlike) {
  std::mt19937 rng(42);
  AppearanceIndex index(/*block_size=*/8);
  std::vector<cv::Mat> stored;
  for (int node = 0; node < 30; ++node) {  // 3 sealed k-d tree blocks and a brute-force tail
    stored.push_back(RandomDescriptors(rng, 40));
    index.Add(node, stored.back());
  }
  for (const int target : {3, 17, 29}) {
    // Half of the target's descriptors, slightly perturbed, plus unrelated ones.
    cv::Mat query = stored[static_cast<std::size_t>(target)].rowRange(0, 20).clone();
    query += RandomDescriptors(rng, 20) * 0.05;
    query.push_back(RandomDescriptors(rng, 20));
    const auto votes = index.Query(query, 3, 3, [](int) { return true; });
    ASSERT_FALSE(votes.empty());
    EXPECT_EQ(votes.front().node, target);
    EXPECT_GE(votes.front().votes, 15);
    // Excluding the target, no key map gathers more than a few chance votes.
    const auto others = index.Query(query, 3, 1, [target](int n) { return n != target; });
    EXPECT_TRUE(others.empty() || others.front().votes <= 3);
  }
}

}  // namespace
}  // namespace gridslam::loop_closure
