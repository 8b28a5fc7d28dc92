// libFuzzer harness: a benchmark relations file through ReadRelations.
#include <cstdint>

#include "gridslam/io/relations_io.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = gridslam::fuzz::ScratchPath(".relations");
  gridslam::fuzz::WriteScratch(path, data, size);
  (void)gridslam::io::ReadRelations(path);
  return 0;
}
