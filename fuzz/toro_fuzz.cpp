// libFuzzer harness: TORO text through ParseToro, as information and as covariance; an accepted
// graph round-trips through FormatToro.
#include <cstdint>

#include "gridslam/io/toro_io.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gridslam::io;
  const std::string text = gridslam::fuzz::AsString(data, size);
  for (const bool covariance : {false, true}) {
    ToroReadOptions options;
    options.covariance = covariance;
    const auto graph = ParseToro(text, "fuzz.graph", nullptr, options);
    if (!graph.ok()) {
      continue;
    }
    const auto again = ParseToro(FormatToro(graph.value()), "again.graph");
    if (!again.ok() || again.value().num_edges() != graph.value().num_edges()) {
      __builtin_trap();
    }
  }
  return 0;
}
