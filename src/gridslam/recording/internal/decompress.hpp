// Chunk decompression for bags: bzip2 and LZ4 frame (ROS 1 bags), zstd and LZ4 frame (MCAP).
// The expected size comes from the container; a mismatch or a corrupt stream is an error.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gridslam/common/result.hpp"

namespace gridslam::recording::internal {

enum class Compression { kNone, kBz2, kLz4Frame, kZstd };

Result<std::vector<std::uint8_t>> Decompress(std::span<const std::uint8_t> input,
                                             Compression compression,
                                             std::size_t uncompressed_size);

}  // namespace gridslam::recording::internal
