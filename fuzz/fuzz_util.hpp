// Helpers shared by the libFuzzer harnesses: the input as a string, and a per-process scratch
// file for the readers that take a path (in /dev/shm when it exists, so no disk I/O).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace gridslam::fuzz {

inline std::string AsString(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// A scratch file path unique to this process, with the given extension.
inline std::string ScratchPath(const std::string& extension) {
  const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm")
                                        ? "/dev/shm"
                                        : std::filesystem::temp_directory_path();
  return (dir / ("gridslam_fuzz_" + std::to_string(::getpid()) + extension)).string();
}

/// Writes `bytes` to `path` (whole, binary).
inline void WriteScratch(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    __builtin_trap();  // the harness itself is broken
  }
  if (size > 0 && std::fwrite(data, 1, size, f) != size) {
    __builtin_trap();
  }
  std::fclose(f);
}

}  // namespace gridslam::fuzz
