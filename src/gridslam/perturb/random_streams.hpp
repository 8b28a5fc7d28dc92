// The random streams of `gridslam perturb`: one per fault, so that turning one fault on or off
// never changes another's draws (simulation::Random(seed, stream)).
#pragma once

#include <cstdint>

namespace gridslam::perturb {

inline constexpr std::uint64_t kStreamGlitches = 161;
inline constexpr std::uint64_t kStreamTimeJitter = 162;
inline constexpr std::uint64_t kStreamRangeNoise = 163;
inline constexpr std::uint64_t kStreamBeamDropout = 164;

}  // namespace gridslam::perturb
