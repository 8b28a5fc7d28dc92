// libFuzzer harness: a trajectory file (timestamp x y theta, or TUM) through ReadTrajectory,
// and the scan index and route readers of the simulator.
#include <cstdint>

#include "gridslam/io/simulation_io.hpp"
#include "gridslam/io/trajectory_io.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = gridslam::fuzz::ScratchPath(".txt");
  gridslam::fuzz::WriteScratch(path, data, size);
  (void)gridslam::io::ReadTrajectory(path);
  (void)gridslam::io::ReadScanIndex(path);
  (void)gridslam::io::ReadWaypoints(path);
  return 0;
}
