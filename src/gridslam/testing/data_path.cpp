#include "gridslam/testing/data_path.hpp"

#include <cstdlib>
#include <random>

#ifndef GRIDSLAM_SOURCE_DIR
#error "GRIDSLAM_SOURCE_DIR must be defined"
#endif

namespace gridslam::testing {

std::filesystem::path DataDir() {
  if (const char* env = std::getenv("GRIDSLAM_DATA"); env != nullptr && *env != '\0') {
    return env;
  }
  return std::filesystem::path(GRIDSLAM_SOURCE_DIR).parent_path() / "shared" / "data";
}

bool HaveData() { return std::filesystem::is_directory(DataDir()); }

std::filesystem::path FixtureDir() {
  return std::filesystem::path(GRIDSLAM_SOURCE_DIR) / "tests" / "data";
}

std::filesystem::path MakeTempDir(const std::string& name) {
  std::random_device rd;
  const auto dir =
      std::filesystem::temp_directory_path() / ("gridslam_" + name + "_" + std::to_string(rd()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace gridslam::testing
