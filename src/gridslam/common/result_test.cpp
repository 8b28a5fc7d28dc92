#include "gridslam/common/result.hpp"

#include <gtest/gtest.h>

namespace gridslam {
namespace {

Result<int> ParsePositive(int x) {
  if (x <= 0) {
    return InvalidInput("not positive", "input.txt", 7);
  }
  return x;
}

Status Chain(int x) {
  GRIDSLAM_RETURN_IF_ERROR(ParsePositive(x));
  return Status::Ok();
}

TEST(Result, CarriesValueOrError) {
  const auto good = ParsePositive(3);
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(good.value(), 3);
  const auto bad = ParsePositive(-1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().ToString(), "input.txt:7: not positive");
  EXPECT_EQ(bad.error().code, ErrorCode::kInvalidInput);
}

TEST(Result, ReturnIfErrorPropagates) {
  EXPECT_TRUE(Chain(2).ok());
  const Status s = Chain(0);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().line, 7);
}

TEST(CheckDeathTest, AbortsWithMessage) {
  EXPECT_DEATH(GRIDSLAM_CHECK(1 + 1 == 3) << "arithmetic", "check failed: 1 \\+ 1 == 3 arithmetic");
}

}  // namespace
}  // namespace gridslam
