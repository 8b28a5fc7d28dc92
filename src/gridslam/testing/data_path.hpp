// Test helpers: where the shared datasets are (GRIDSLAM_DATA, default ../shared/data beside the
// project root) and a macro that skips a test, visibly, only when that folder is absent.
#pragma once

#include <filesystem>
#include <string>

namespace gridslam::testing {

/// $GRIDSLAM_DATA, or <project root>/../shared/data.
std::filesystem::path DataDir();
/// True when DataDir() exists.
bool HaveData();
/// <project root>/tests/data, the committed small fixtures.
std::filesystem::path FixtureDir();
/// A fresh empty temporary folder for one test.
std::filesystem::path MakeTempDir(const std::string& name);

}  // namespace gridslam::testing

#define GRIDSLAM_REQUIRE_DATA()                                                         \
  do {                                                                                  \
    if (!::gridslam::testing::HaveData()) {                                             \
      GTEST_SKIP() << "shared datasets not found at " << ::gridslam::testing::DataDir() \
                   << " (set GRIDSLAM_DATA)";                                           \
    }                                                                                   \
  } while (false)
