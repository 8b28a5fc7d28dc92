// Reading the project's CARMEN logs through the streaming reader (parse, timestamp repair,
// odometry interpolation): time per log and scans per second. Reads $GRIDSLAM_DATA/logs; a log
// that is absent is reported as skipped.
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/testing/data_path.hpp"

namespace {

void ReadLog(benchmark::State& state, const std::string& name) {
  const std::string path = (gridslam::testing::DataDir() / "logs" / name).string();
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("missing " + path).c_str());
    return;
  }
  long scans = 0;
  for (auto _ : state) {
    auto reader = gridslam::io::CarmenReader::Open(path, {});
    if (!reader.ok()) {
      state.SkipWithError(reader.error().ToString().c_str());
      return;
    }
    long n = 0;
    while (true) {
      auto next = reader.value().Next();
      if (!next.ok() || !next.value()) {
        break;
      }
      benchmark::DoNotOptimize(next.value()->scan.ranges.data());
      ++n;
    }
    scans = n;
  }
  state.counters["scans"] = static_cast<double>(scans);
  state.counters["scans_per_s"] =
      benchmark::Counter(static_cast<double>(scans) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(ReadLog, intel, std::string("intel.reconstructed.clf"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ReadLog, fr079, std::string("fr079.reconstructed.clf"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ReadLog, fr_clinic, std::string("fr-clinic.reconstructed.clf"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ReadLog, fr101, std::string("fr101.carmen.log"))->Unit(benchmark::kMillisecond);

}  // namespace
