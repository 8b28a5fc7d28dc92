// Issue 17's YAML reproducers: duplicate keys, non-scalar keys, special floats that must read
// back, and validation errors that name the file and the option's line.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "gridslam/common/options.hpp"
#include "gridslam/io/options_yaml.hpp"

namespace gridslam::io {
namespace {

struct Inner {
  double range = 80.0;
  double resolution = 0.05;
  template <class V>
  void Visit(V& v) {
    v("range", range, "Usable range [m]");
    v("resolution", resolution, "Cell side [m]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(range > 0.0, "inner.range > 0"));
    return Require(resolution >= 0.01, "inner.resolution >= 0.01");
  }
};

struct Outer {
  int count = 3;
  Inner inner;
  template <class V>
  void Visit(V& v) {
    v("count", count, "A count");
    v.Section("inner", inner, "Inner component");
  }
  [[nodiscard]] Status Validate() const { return inner.Validate(); }
};

Error Load(const std::string& yaml) {
  Outer options;
  const Status s = LoadOptionsFromString(yaml, "c.yaml", options);
  EXPECT_FALSE(s.ok()) << "accepted:\n" << yaml;
  return s.ok() ? Error{} : s.error();
}

TEST(OptionsYamlBadInput, DuplicateKeyIsAnError) {
  const Error e = Load("count: 1\ninner:\n  range: 2\n  range: 3\n");
  EXPECT_EQ(e.code, ErrorCode::kInvalidInput);
  EXPECT_EQ(e.file, "c.yaml");
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("'inner.range' given twice"), std::string::npos) << e.ToString();
  const Error top = Load("count: 1\ncount: 2\n");
  EXPECT_EQ(top.line, 2);
}

TEST(OptionsYamlBadInput, NonScalarKeyIsACleanError) {
  for (const char* yaml : {"? [a, b]\n: 1\n", "inner:\n  ? {x: 1}\n  : 2\n", "[1, 2]: 3\n"}) {
    const Error e = Load(yaml);
    EXPECT_EQ(e.code, ErrorCode::kInvalidInput);
    EXPECT_EQ(e.file, "c.yaml");
    EXPECT_GT(e.line, 0);
  }
}

TEST(OptionsYamlBadInput, ValidationErrorsNameFileAndLine) {
  const Error e = Load("count: 1\ninner:\n  range: 5\n  resolution: 0.0001\n");
  EXPECT_EQ(e.file, "c.yaml");
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("inner.resolution"), std::string::npos);
  const Error range = Load("inner: {range: -1, resolution: 1}\n");
  EXPECT_EQ(range.line, 1);
}

TEST(OptionsYamlBadInput, InfinityIsWrittenSoItReadsBack) {
  Outer options;
  options.inner.range = std::numeric_limits<double>::infinity();
  const std::string yaml = OptionsToYaml(options);
  EXPECT_NE(yaml.find("range: .inf"), std::string::npos) << yaml;
  Outer read;
  ASSERT_TRUE(LoadOptionsFromString(yaml, "c.yaml", read).ok());
  EXPECT_TRUE(std::isinf(read.inner.range));
  options.inner.range = -std::numeric_limits<double>::infinity();
  EXPECT_NE(OptionsToYaml(options).find("range: -.inf"), std::string::npos);
}

}  // namespace
}  // namespace gridslam::io
