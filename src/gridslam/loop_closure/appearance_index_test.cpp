#include "gridslam/loop_closure/appearance_index.hpp"

#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

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

// The query (half of the target's descriptors, perturbed, plus unrelated ones) votes for the
// target; excluding it, no key map gathers more than a few chance votes.
void ExpectVotesFor(const AppearanceIndex& index, const cv::Mat& query, int target) {
  const auto votes = index.Query(query, 3, 3, [](int) { return true; });
  ASSERT_FALSE(votes.empty());
  EXPECT_EQ(votes.front().node, target);
  EXPECT_GE(votes.front().votes, 15);
  const auto others = index.Query(query, 3, 1, [target](int n) { return n != target; });
  EXPECT_TRUE(others.empty() || others.front().votes <= 3);
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
    ExpectVotesFor(index, query, target);
  }
}

cv::Mat RandomBits(std::mt19937& rng, int rows) {
  std::uniform_int_distribution<int> byte(0, 255);
  cv::Mat d(rows, 61, CV_8U);  // AKAZE's 486-bit descriptor
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < d.cols; ++c) {
      d.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(byte(rng));
    }
  }
  return d;
}

// Binary descriptors (ORB, AKAZE) were once ignored, which silently disabled the appearance
// search (no joins of robots) for those detectors.
TEST(AppearanceIndex, BinaryDescriptorsVoteByHammingDistance) {
  std::mt19937 rng(7);
  AppearanceIndex index(/*block_size=*/8);
  std::vector<cv::Mat> stored;
  for (int node = 0; node < 20; ++node) {
    stored.push_back(RandomBits(rng, 40));
    index.Add(node, stored.back());
  }
  index.Add(99, RandomDescriptors(rng, 40));  // another type: ignored
  std::bernoulli_distribution flip(0.05);
  for (const int target : {2, 13, 19}) {
    cv::Mat query = stored[static_cast<std::size_t>(target)].rowRange(0, 20).clone();
    for (int r = 0; r < query.rows; ++r) {
      for (int c = 0; c < query.cols; ++c) {
        for (int bit = 0; bit < 8; ++bit) {
          if (flip(rng)) {
            query.at<std::uint8_t>(r, c) ^= static_cast<std::uint8_t>(1U << bit);
          }
        }
      }
    }
    query.push_back(RandomBits(rng, 20));
    ExpectVotesFor(index, query, target);
  }
  EXPECT_TRUE(index.Query(RandomDescriptors(rng, 5), 3, 1, [](int) { return true; }).empty());
}

// FLANN's randomized trees come from the index's random state, not from the calling thread's
// cv::theRNG(): an index built on another thread, or after other code drew random numbers,
// answers the same (the mapper's results must not depend on its threads).
TEST(AppearanceIndex, TreesDoNotDependOnTheThreadOrOnOtherRandomNumbers) {
  std::mt19937 rng(5);
  std::vector<cv::Mat> stored;
  for (int node = 0; node < 140; ++node) {  // two sealed blocks of 64 and a tail
    stored.push_back(RandomDescriptors(rng, 40));
  }
  std::vector<cv::Mat> queries;
  for (int q = 0; q < 10; ++q) {
    queries.push_back(RandomDescriptors(rng, 30));
  }
  const auto answers = [&]() {
    AppearanceIndex index;
    for (int node = 0; node < 140; ++node) {
      index.Add(node, stored[static_cast<std::size_t>(node)]);
    }
    std::vector<std::vector<std::pair<int, int>>> all;
    for (const cv::Mat& query : queries) {
      all.emplace_back();
      for (const AppearanceVote& v : index.Query(query, 10, 1, [](int) { return true; })) {
        all.back().emplace_back(v.node, v.votes);
      }
    }
    return all;
  };
  const auto here = answers();
  for (int k = 0; k < 1000; ++k) {
    (void)cv::theRNG().next();
  }
  EXPECT_EQ(answers(), here);
  std::vector<std::vector<std::pair<int, int>>> there;
  std::thread([&] {
    (void)cv::theRNG().next();
    there = answers();
  }).join();
  EXPECT_EQ(there, here);
}

}  // namespace
}  // namespace gridslam::loop_closure
