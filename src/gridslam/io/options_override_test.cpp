// --set overrides (ApplyOptionOverride) and validation errors located in the YAML text.
#include <gtest/gtest.h>

#include "gridslam/common/options.hpp"
#include "gridslam/io/options_yaml.hpp"

namespace gridslam::io {
namespace {

struct Inner {
  double range = 80.0;
  std::vector<double> offset = {0.0, 0.0, 0.0};
  template <class V>
  void Visit(V& v) {
    v("range", range, "Usable range [m]");
    v("offset", offset, "Offset [m]");
  }
  [[nodiscard]] Status Validate() const { return Require(range > 0.0, "inner.range > 0"); }
};

struct Outer {
  std::string name = "intel";
  bool flag = false;
  Inner inner;
  template <class V>
  void Visit(V& v) {
    v("name", name, "A name");
    v("flag", flag, "A flag");
    v.Section("inner", inner, "Inner component");
  }
  [[nodiscard]] Status Validate() const { return inner.Validate(); }
};

TEST(OptionOverride, SetsScalarsListsAndStringsAsYaml) {
  Outer o;
  ASSERT_TRUE(ApplyOptionOverride("inner.range=12.5", o).ok());
  ASSERT_TRUE(ApplyOptionOverride("inner.offset=[0.2, 0, -1]", o).ok());
  ASSERT_TRUE(ApplyOptionOverride("name=fr079", o).ok());
  ASSERT_TRUE(ApplyOptionOverride("flag=true", o).ok());
  EXPECT_EQ(o.inner.range, 12.5);
  EXPECT_EQ(o.inner.offset, (std::vector<double>{0.2, 0.0, -1.0}));
  EXPECT_EQ(o.name, "fr079");
  EXPECT_TRUE(o.flag);
}

TEST(OptionOverride, ErrorsNameTheAssignment) {
  Outer o;
  const Status unknown = ApplyOptionOverride("inner.rnage=1", o);
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().file, "--set inner.rnage=1");
  EXPECT_EQ(unknown.error().line, 0);
  EXPECT_NE(unknown.error().message.find("inner.rnage"), std::string::npos);
  EXPECT_FALSE(ApplyOptionOverride("inner.range", o).ok());
  EXPECT_FALSE(ApplyOptionOverride("=1", o).ok());
  EXPECT_FALSE(ApplyOptionOverride("inner range=1", o).ok());
  EXPECT_FALSE(ApplyOptionOverride("inner.range=abc", o).ok());
  EXPECT_FALSE(ApplyOptionOverride("inner=1", o).ok());  // a section, not a value
  EXPECT_EQ(o.inner.range, 80.0);
}

TEST(OptionOverride, DoesNotValidate) {
  Outer o;
  ASSERT_TRUE(ApplyOptionOverride("inner.range=-1", o).ok());
  EXPECT_FALSE(o.Validate().ok());
}

TEST(OptionsValidation, ErrorNamesFileAndLineOfTheKey) {
  Outer o;
  const Status s = LoadOptionsFromString("name: x\n\ninner:\n  range: -2\n", "my.yaml", o);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().file, "my.yaml");
  EXPECT_EQ(s.error().line, 4);
  Outer flow;
  const Status f = LoadOptionsFromString("inner: {range: -1}\n", "flow.yaml", flow);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.error().line, 1);
}

TEST(OptionsValidation, KeyNotInTheTextGivesTheFileOnly) {
  Outer o;
  o.inner.range = -1.0;  // invalid before the file is read; the file does not set it
  const Status s = LoadOptionsFromString("name: x\n", "my.yaml", o);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().file, "my.yaml");
  EXPECT_EQ(s.error().line, 0);
}

TEST(OptionsValidation, FindOptionLineMatchesWholeComponents) {
  const YAML::Node root = YAML::Load("a:\n  xrange: 1\n  b:\n    range: 2\n");
  EXPECT_EQ(internal::FindOptionLine(root, "b.range"), 4);
  EXPECT_EQ(internal::FindOptionLine(root, "range"), 4);  // not xrange
  EXPECT_EQ(internal::FindOptionLine(root, "c.range"), 0);
}

}  // namespace
}  // namespace gridslam::io
