#include "gridslam/common/thread_scratch.hpp"

#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

struct BufferTag {};
struct OtherTag {};
using Buffer = std::vector<int>;

Buffer& First() { return ThreadScratch<BufferTag, Buffer>(); }
Buffer& Second() { return ThreadScratch<OtherTag, Buffer>(); }

TEST(ThreadScratch, KeptBetweenCallsOnOneThread) {
  Buffer& first = First();
  first.assign(1000, 7);
  Buffer& again = First();
  EXPECT_EQ(&first, &again);
  ASSERT_EQ(again.size(), 1000U);
  EXPECT_EQ(again[999], 7);
  ReleaseThreadScratch();
}

TEST(ThreadScratch, TagsAndThreadsDoNotShare) {
  First().assign(10, 1);
  Second().assign(20, 2);
  EXPECT_EQ(First().size(), 10U);
  std::size_t seen_by_other_thread = 99;
  std::thread([&] { seen_by_other_thread = First().size(); }).join();
  EXPECT_EQ(seen_by_other_thread, 0U);
  ReleaseThreadScratch();
}

TEST(ThreadScratch, ReleaseFreesEveryBufferOfTheCallingThreadOnly) {
  First().assign(1 << 16, 3);
  Second().assign(1 << 12, 4);
  std::size_t other_thread_capacity = 0;
  std::thread([&] {
    First().assign(100, 5);
    // A release on this thread leaves the main thread's buffers alone.
    ReleaseThreadScratch();
    other_thread_capacity = First().capacity();
  }).join();
  EXPECT_EQ(other_thread_capacity, 0U);
  EXPECT_EQ(First().size(), std::size_t{1} << 16);
  ReleaseThreadScratch();
  EXPECT_EQ(First().capacity(), 0U);
  EXPECT_EQ(Second().capacity(), 0U);
  // Usable again after a release.
  First().assign(3, 9);
  EXPECT_EQ(First()[2], 9);
  ReleaseThreadScratch();
}

}  // namespace
}  // namespace gridslam
