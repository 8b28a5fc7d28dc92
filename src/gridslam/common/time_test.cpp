#include "gridslam/common/time.hpp"

#include <limits>

#include <gtest/gtest.h>

namespace gridslam {
namespace {

TEST(Time, ParsesCarmenTimestampsExactly) {
  const auto t = ParseSeconds("976052864.458620");
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->time_since_epoch().count(), 976052864458620000LL);
  EXPECT_EQ(FormatSeconds(*t), "976052864.458620");
}

TEST(Time, ParsesNegativeIntegerAndShortFractions) {
  EXPECT_EQ(ParseSeconds("-0.958593")->time_since_epoch().count(), -958593000LL);
  EXPECT_EQ(ParseSeconds("12")->time_since_epoch().count(), 12000000000LL);
  EXPECT_EQ(ParseSeconds("1.5")->time_since_epoch().count(), 1500000000LL);
  EXPECT_EQ(ParseSeconds("1e3")->time_since_epoch().count(), 1000000000000LL);
  EXPECT_EQ(FormatSeconds(*ParseSeconds("-0.958593")), "-0.958593");
  EXPECT_EQ(FormatSeconds(*ParseSeconds("1211.5"), 3), "1211.500");
}

TEST(Time, RejectsMalformedText) {
  EXPECT_FALSE(ParseSeconds("").has_value());
  EXPECT_FALSE(ParseSeconds("abc").has_value());
  EXPECT_FALSE(ParseSeconds("1.2.3").has_value());
  EXPECT_FALSE(ParseSeconds("-").has_value());
  EXPECT_FALSE(ParseSeconds("12x").has_value());
}

TEST(Time, RoundTripsThroughDoubleSeconds) {
  const Time t = FromSeconds(1211.25);
  EXPECT_DOUBLE_EQ(ToSeconds(t), 1211.25);
  EXPECT_DOUBLE_EQ(ToSeconds(SecondsToDuration(0.1)), 0.1);
}

// Issue 17: "20000000000.000000" overflowed int64 nanoseconds and read as 1553255926.290448.
TEST(Time, RejectsTimestampsBeyondInt64Nanoseconds) {
  EXPECT_FALSE(ParseSeconds("20000000000.000000").has_value());
  EXPECT_FALSE(ParseSeconds("-20000000000").has_value());
  EXPECT_FALSE(ParseSeconds("99999999999999999999999").has_value());
  EXPECT_FALSE(ParseSeconds("1e308").has_value());
  EXPECT_FALSE(ParseSeconds("-1e10").has_value());
  ASSERT_TRUE(ParseSeconds("9000000000.5").has_value());
  EXPECT_EQ(FormatSeconds(*ParseSeconds("9000000000.5")), "9000000000.500000");
  EXPECT_EQ(FormatSeconds(*ParseSeconds("-8999999999.25")), "-8999999999.250000");
}

// Issue 17: the most negative time was printed as "--9223372036.-854775".
TEST(Time, FormatsTheExtremeTimes) {
  const Time lowest = Time(Duration(std::numeric_limits<std::int64_t>::min()));
  const Time highest = Time(Duration(std::numeric_limits<std::int64_t>::max()));
  EXPECT_EQ(FormatSeconds(lowest, 9), "-9223372036.854775808");
  EXPECT_EQ(FormatSeconds(highest, 9), "9223372036.854775807");
  EXPECT_EQ(FormatSeconds(lowest, 6), "-9223372036.854776");
}

}  // namespace
}  // namespace gridslam
