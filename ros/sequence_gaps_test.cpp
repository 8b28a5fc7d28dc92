#include "sequence_gaps.hpp"

#include <gtest/gtest.h>

namespace gridslam::live {
namespace {

TEST(SequenceGaps, CountsGapsOnceTheyLeaveTheWindow) {
  SequenceGaps gaps(10);
  for (std::uint32_t s = 5; s < 20; ++s) {
    EXPECT_EQ(gaps.Add(s), 0);
  }
  EXPECT_EQ(gaps.Add(23), 0);  // 20..22 missing, but could still come
  for (std::uint32_t s = 24; s < 33; ++s) {
    gaps.Add(s);
  }
  EXPECT_EQ(gaps.Add(33), 3);  // 20..22 are now 11 behind the newest: lost
  EXPECT_EQ(gaps.Lost(), 3);
}

TEST(SequenceGaps, LateArrivalsWithinTheWindowAreNotLost) {
  SequenceGaps gaps(10);
  for (const std::uint32_t s : {0U, 1U, 3U, 4U, 2U, 5U, 7U, 6U, 8U, 9U, 10U, 11U, 12U, 13U, 14U}) {
    gaps.Add(s);
  }
  for (std::uint32_t s = 15; s < 40; ++s) {
    gaps.Add(s);
  }
  EXPECT_EQ(gaps.Lost(), 0);
}

TEST(SequenceGaps, ANewPublisherStartsAgainAndLongGapsCount) {
  SequenceGaps gaps(10);
  gaps.Add(1000);
  gaps.Add(1002);             // 1001 pending
  EXPECT_EQ(gaps.Add(0), 1);  // far behind: a new publisher; its predecessor's gap is lost
  EXPECT_EQ(gaps.Add(1), 1);
  EXPECT_EQ(gaps.Add(500'002), 500'001);  // a long gap counts at once
}

}  // namespace
}  // namespace gridslam::live
