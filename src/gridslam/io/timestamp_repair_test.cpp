#include "gridslam/io/timestamp_repair.hpp"

#include <string>

#include <gtest/gtest.h>

namespace gridslam::io {
namespace {

Time T(const std::string& text) { return *ParseSeconds(text); }

std::vector<Time> RunRepair(const std::vector<std::string>& texts, std::size_t lag = 32) {
  TimestampRepairer repair(lag, /*detect_count=*/100, /*min_count=*/5);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    repair.Push(i, texts[i], T(texts[i]));
  }
  repair.Flush();
  std::vector<Time> out;
  while (auto r = repair.Pop()) {
    EXPECT_EQ(r->first, out.size());
    out.push_back(r->second);
  }
  return out;
}

TEST(TimestampRepair, CandidatesDropTrailingZeros) {
  const auto c = UnpaddedCandidates("976052864.458620", T("976052864.458620"));
  ASSERT_EQ(c.size(), 2U);
  EXPECT_EQ(FormatSeconds(c[1]), "976052864.045862");
  const auto d = UnpaddedCandidates("111.730000", T("111.730000"));
  ASSERT_EQ(d.size(), 5U);
  EXPECT_EQ(FormatSeconds(d[4]), "111.000073");
  EXPECT_EQ(UnpaddedCandidates("5.123457", T("5.123457")).size(), 1U);
  EXPECT_EQ(UnpaddedCandidates("5.10", T("5.10")).size(), 1U);  // not 6 decimals
  EXPECT_EQ(UnpaddedCandidates("5.000000", T("5.000000")).size(), 1U);
}

TEST(TimestampRepair, DetectsTheBugFromMissingSmallFractions) {
  EXPECT_TRUE(HasSmallFraction("12.012345"));
  EXPECT_TRUE(HasSmallFraction("12"));
  EXPECT_FALSE(HasSmallFraction("12.458620"));
}

TEST(TimestampRepair, FixesUnpaddedRuns) {
  // A run of two unpadded times: 4.073456 and 4.075987 printed as 4.734560 and 4.759870.
  const std::vector<std::string> texts = {"3.812345", "3.912345", "4.734560", "4.759870",
                                          "4.165431", "4.265437", "4.365439"};
  const auto out = RunRepair(texts);
  ASSERT_EQ(out.size(), texts.size());
  EXPECT_EQ(FormatSeconds(out[2]), "4.073456");
  EXPECT_EQ(FormatSeconds(out[3]), "4.075987");
  EXPECT_EQ(out[0], T(texts[0]));
  EXPECT_EQ(out[4], T(texts[4]));
}

TEST(TimestampRepair, CorrectLogIsLeftAlone) {
  // A small fraction (4.012340) shows the times are padded: out-of-order lines stay as printed.
  const std::vector<std::string> texts = {"3.900000", "4.500000", "4.012340",
                                          "4.600000", "4.700000", "4.800000"};
  const auto out = RunRepair(texts);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    EXPECT_EQ(out[i], T(texts[i]));
  }
}

TEST(TimestampRepair, MonotonicStreamUnchangedWithShortLag) {
  std::vector<std::string> texts;
  for (int k = 1; k < 60; ++k) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%d.%d00000", 10 + k / 9, 1 + k % 9);
    texts.emplace_back(buf);
  }
  const auto out = RunRepair(texts, /*lag=*/4);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    EXPECT_EQ(out[i], T(texts[i])) << texts[i];
  }
}

}  // namespace
}  // namespace gridslam::io
