// A small deterministic random source for the simulator: SplitMix64 seeding and xoshiro256**
// (Blackman & Vigna 2018), with uniform and Gaussian draws implemented here rather than by the
// standard library's distributions, whose algorithms differ between implementations. The same
// seed therefore gives the same numbers on every platform, which makes simulated logs
// byte-identical for a given seed.
#pragma once

#include <array>
#include <cstdint>

namespace gridslam::simulation {

class Random {
 public:
  /// A stream determined by `seed` and `stream` (e.g. robot index and purpose): streams with
  /// different numbers are independent for practical purposes.
  explicit Random(std::uint64_t seed, std::uint64_t stream = 0);

  /// 64 random bits.
  std::uint64_t Next();
  /// Uniform in [0, 1).
  double Uniform();
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Standard normal (Marsaglia's polar method).
  double Gaussian();
  /// Normal with standard deviation `sigma` (0 gives 0 and consumes no numbers).
  double Gaussian(double sigma) { return sigma > 0.0 ? sigma * Gaussian() : 0.0; }
  /// True with probability p (p <= 0 consumes no numbers).
  bool Bernoulli(double p) { return p > 0.0 && Uniform() < p; }

 private:
  std::array<std::uint64_t, 4> s_{};
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace gridslam::simulation
