#include "gridslam/io/atomic_file.hpp"

#include <cstdio>
#include <filesystem>
#include <random>

#include <unistd.h>

namespace gridslam::io {

Status WriteFileAtomically(const std::string& path, const std::string& contents) {
  std::random_device device;
  const std::string temp =
      path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(device() % 1000000U);
  std::FILE* f = std::fopen(temp.c_str(), "wb");
  if (f == nullptr) {
    return RuntimeError("cannot write '" + path + "' (cannot create '" + temp + "')");
  }
  const bool written = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
  const bool flushed = std::fflush(f) == 0;
  const bool closed = std::fclose(f) == 0;
  if (!written || !flushed || !closed) {
    std::remove(temp.c_str());
    return RuntimeError("cannot write '" + path + "' (write failed)");
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::remove(temp.c_str());
    return RuntimeError("cannot write '" + path + "': " + ec.message());
  }
  return Status::Ok();
}

}  // namespace gridslam::io
