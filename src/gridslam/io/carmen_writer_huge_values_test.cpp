#include <string>

#include <gtest/gtest.h>

#include "gridslam/io/carmen_writer.hpp"

namespace gridslam::io {
namespace {

// Issue 17: `split` of a log holding 1e308 wrote stack bytes (carmen_writer.cpp:30 read past a
// 64-byte buffer). A huge value is now printed whole.
TEST(CarmenBadNumbers, WriterPrintsHugeValuesWhole) {
  const std::string line =
      FormatOdometryLine({Time(), Pose2(1e308, -1e300, 0.0), 1e200, 0.0, 0.0}, "h", Time());
  const std::size_t first_space = line.find(' ');
  const std::size_t second_space = line.find(' ', first_space + 1);
  const std::string x = line.substr(first_space + 1, second_space - first_space - 1);
  EXPECT_EQ(x.size(), 309U + 7U);  // 309 digits, ".000000"
  EXPECT_EQ(x.substr(0, 5), "10000");
  EXPECT_EQ(x.find_first_not_of("0123456789."), std::string::npos) << x;
  EXPECT_NE(line.find(" h 0.000000\n"), std::string::npos);
}

}  // namespace
}  // namespace gridslam::io
