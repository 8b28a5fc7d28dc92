#include "gridslam/common/parallel.hpp"

#include <atomic>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

TEST(PartCount, AtLeastOneAtMostTheItems) {
  EXPECT_EQ(PartCount(0, 4), 1U);
  EXPECT_EQ(PartCount(10, 0), 1U);
  EXPECT_EQ(PartCount(10, -3), 1U);
  EXPECT_EQ(PartCount(10, 2), 2U);
  EXPECT_EQ(PartCount(3, 8), 3U);
}

TEST(RunParts, EveryItemOnceInContiguousRanges) {
  for (const std::size_t n : {0U, 1U, 2U, 7U, 100U}) {
    for (const int threads : {1, 2, 3, 8}) {
      const std::size_t parts = PartCount(n, threads);
      std::vector<int> seen(n, 0);
      std::vector<int> part_of(n, -1);
      RunParts(n, parts, [&](std::size_t part, std::size_t begin, std::size_t end) {
        ASSERT_LE(begin, end);
        for (std::size_t k = begin; k < end; ++k) {
          ++seen[k];  // disjoint ranges: no two threads touch one item
          part_of[k] = static_cast<int>(part);
        }
      });
      for (std::size_t k = 0; k < n; ++k) {
        EXPECT_EQ(seen[k], 1) << "n " << n << " threads " << threads << " item " << k;
        if (k > 0) {
          EXPECT_GE(part_of[k], part_of[k - 1]);  // parts in order along the items
        }
      }
    }
  }
}

TEST(RunParts, OtherPartsRunOnOtherThreads) {
  std::atomic<int> others{0};
  const auto caller = std::this_thread::get_id();
  RunParts(4, 4, [&](std::size_t part, std::size_t, std::size_t) {
    if (part > 0 && std::this_thread::get_id() != caller) {
      ++others;
    }
  });
  EXPECT_EQ(others.load(), 3);
}

}  // namespace
}  // namespace gridslam
