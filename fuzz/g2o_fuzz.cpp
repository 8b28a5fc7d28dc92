// libFuzzer harness: g2o text through ParseG2o; an accepted graph must have finite numbers and
// positive definite information, and must survive a write/read round trip unchanged in size.
#include <cmath>
#include <cstdint>

#include <Eigen/LU>

#include "gridslam/io/g2o_io.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gridslam::io;
  const auto graph = ParseG2o(gridslam::fuzz::AsString(data, size), "fuzz.g2o");
  if (!graph.ok()) {
    return 0;
  }
  for (const auto& e : graph.value().edges()) {
    if (!e.information.allFinite() || !(e.information.determinant() > 0.0)) {
      __builtin_trap();
    }
  }
  const auto again = ParseG2o(FormatG2o(graph.value()), "again.g2o");
  if (!again.ok() || again.value().num_vertices() != graph.value().num_vertices() ||
      again.value().num_edges() != graph.value().num_edges()) {
    __builtin_trap();
  }
  return 0;
}
