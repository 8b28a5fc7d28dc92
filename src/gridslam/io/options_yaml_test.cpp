#include "gridslam/io/options_yaml.hpp"

#include <gtest/gtest.h>

#include "gridslam/common/options.hpp"

namespace gridslam::io {
namespace {

struct InnerOptions {
  double range = 80.0;
  std::vector<double> sentinels = {81.83, 81.91};
  template <class V>
  void Visit(V& v) {
    v("range", range, "Usable range [m]");
    v("sentinels", sentinels, "No-return values [m]");
  }
  [[nodiscard]] Status Validate() const { return Require(range > 0.0, "inner.range > 0"); }
  bool operator==(const InnerOptions&) const = default;
};

struct OuterOptions {
  int count = 3;
  bool flag = false;
  std::string name = "intel";
  InnerOptions inner;
  template <class V>
  void Visit(V& v) {
    v("count", count, "A count");
    v("flag", flag, "A flag");
    v("name", name, "A name");
    v.Section("inner", inner, "Inner component");
  }
  [[nodiscard]] Status Validate() const { return inner.Validate(); }
  bool operator==(const OuterOptions&) const = default;
};

TEST(OptionsYaml, DefaultsRoundTrip) {
  OuterOptions changed;
  changed.count = 9;
  changed.flag = true;
  changed.name = "fr079";
  changed.inner.range = 12.5;
  changed.inner.sentinels = {1.0};
  OuterOptions read;
  ASSERT_TRUE(LoadOptionsFromString(OptionsToYaml(changed), "x.yaml", read).ok());
  EXPECT_EQ(read, changed);
}

TEST(OptionsYaml, MissingKeysKeepDefaults) {
  OuterOptions read;
  ASSERT_TRUE(LoadOptionsFromString("inner:\n  range: 5\n", "x.yaml", read).ok());
  EXPECT_EQ(read.count, 3);
  EXPECT_DOUBLE_EQ(read.inner.range, 5.0);
}

TEST(OptionsYaml, UnknownKeyIsAnErrorWithLine) {
  OuterOptions read;
  const Status s = LoadOptionsFromString("count: 2\ninner:\n  rnage: 5\n", "x.yaml", read);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("inner.rnage"), std::string::npos);
  EXPECT_EQ(s.error().line, 3);
  EXPECT_EQ(s.error().file, "x.yaml");
}

TEST(OptionsYaml, WrongTypeAndValidationFail) {
  OuterOptions read;
  EXPECT_FALSE(LoadOptionsFromString("count: abc\n", "x.yaml", read).ok());
  OuterOptions read2;
  EXPECT_FALSE(LoadOptionsFromString("inner: {range: -1}\n", "x.yaml", read2).ok());
  OuterOptions read3;
  EXPECT_FALSE(LoadOptionsFromString("count: [1\n", "x.yaml", read3).ok());
}

}  // namespace
}  // namespace gridslam::io
