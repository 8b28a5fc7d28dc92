#include "gridslam/io/atomic_file.hpp"

#include <cstdio>
#include <filesystem>
#include <random>

#include <unistd.h>

namespace gridslam::io {

namespace {

/// Writes straight into an existing non-regular file (/dev/null, /dev/full, a FIFO): renaming a
/// temporary file over it would replace the device with a regular file.
Status WriteInPlace(const std::string& path, const FileWriter& write) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    return RuntimeError("cannot write '" + path + "' (cannot open it)");
  }
  const bool written = write(f);
  const bool flushed = std::fflush(f) == 0;
  const bool closed = std::fclose(f) == 0;
  if (!written || !flushed || !closed) {
    return RuntimeError("cannot write '" + path + "' (write failed)");
  }
  return Status::Ok();
}

}  // namespace

Status WriteFileAtomically(const std::string& path, const std::string& contents) {
  return WriteFileAtomically(path, [&contents](std::FILE* f) {
    return std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
  });
}

Status WriteFileAtomically(const std::string& path, const FileWriter& write) {
  std::error_code status_error;
  const auto status = std::filesystem::status(path, status_error);
  if (!status_error && std::filesystem::exists(status) &&
      !std::filesystem::is_regular_file(status) && !std::filesystem::is_directory(status)) {
    return WriteInPlace(path, write);
  }
  std::random_device device;
  const std::string temp =
      path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(device() % 1000000U);
  std::FILE* f = std::fopen(temp.c_str(), "wb");
  if (f == nullptr) {
    return RuntimeError("cannot write '" + path + "' (cannot create '" + temp + "')");
  }
  const bool written = write(f);
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
