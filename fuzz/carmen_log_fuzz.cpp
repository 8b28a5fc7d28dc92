// libFuzzer harness: a whole CARMEN log (plain or gzip) through CarmenReader, strict and
// lenient, with and without timestamp repair. Invariant: every delivered frame has a finite
// pose, and frames come in file order of their lines.
#include <cmath>
#include <cstdint>

#include "gridslam/io/carmen_reader.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gridslam::io;
  static const std::string path = gridslam::fuzz::ScratchPath(".clf");
  gridslam::fuzz::WriteScratch(path, data, size);
  for (int pass = 0; pass < 3; ++pass) {
    CarmenOptions options;
    options.lenient = pass >= 1;
    options.repair_timestamps = pass != 2;
    auto reader = CarmenReader::Open(path, options);
    if (!reader.ok()) {
      return 0;
    }
    long last_line = 0;
    for (int k = 0; k < 100000; ++k) {
      auto next = reader.value().Next();
      if (!next.ok() || !next.value()) {
        break;
      }
      const gridslam::Frame& f = *next.value();
      if (!std::isfinite(f.T_odom_base.x()) || !std::isfinite(f.T_odom_base.theta()) ||
          !std::isfinite(f.T_base_laser.x()) || f.source_line <= last_line) {
        __builtin_trap();
      }
      last_line = f.source_line;
    }
    if (reader.value().Stats().scans == 0) {
      (void)NoScansError(path, reader.value().Stats());
    }
  }
  return 0;
}
