// libFuzzer harness: a YAML configuration through LoadOptionsFromString into SlamOptions.
// Invariant: accepted options validate, and what --print-config writes reads back.
#include <cstdint>

#include "gridslam/io/options_yaml.hpp"
#include "gridslam/pipeline/slam_options.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gridslam;
  SlamOptions options;
  if (!io::LoadOptionsFromString(fuzz::AsString(data, size), "fuzz.yaml", options).ok()) {
    return 0;
  }
  SlamOptions again;
  if (!io::LoadOptionsFromString(io::OptionsToYaml(options), "again.yaml", again).ok()) {
    __builtin_trap();
  }
  return 0;
}
