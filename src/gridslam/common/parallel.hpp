// Work split over a few threads (docs/speed.md): n items cut into contiguous parts, each part run
// by one thread. What a part computes must depend only on its range and go to outputs no other
// part writes; the results are then the same whatever the number of threads and their timing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace gridslam {

/// The number of parts RunParts cuts `n` items into for `threads` threads: at least 1, at most
/// max(n, 1).
[[nodiscard]] inline std::size_t PartCount(std::size_t n, int threads) {
  return std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), 1,
                                 std::max<std::size_t>(1, n));
}

/// Runs work(part, begin, end) on the `parts` contiguous ranges [n * p / parts, n * (p + 1) /
/// parts) of [0, n): part 0 on the calling thread, every other part on a thread of its own.
/// Returns when all are done.
template <class Work>
void RunParts(std::size_t n, std::size_t parts, Work&& work) {
  std::vector<std::thread> workers;
  for (std::size_t p = 1; p < parts; ++p) {
    workers.emplace_back([&work, n, p, parts] { work(p, n * p / parts, n * (p + 1) / parts); });
  }
  work(std::size_t{0}, std::size_t{0}, n / std::max<std::size_t>(parts, 1));
  for (std::thread& w : workers) {
    w.join();
  }
}

}  // namespace gridslam
