#include "gridslam/io/internal/gz_line_reader.hpp"

#include <cstring>
#include <utility>

#include <zlib.h>

namespace gridslam::io::internal {

GzLineReader::GzLineReader(GzLineReader&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)), path_(std::move(other.path_)) {}

GzLineReader& GzLineReader::operator=(GzLineReader&& other) noexcept {
  if (this != &other) {
    Close();
    file_ = std::exchange(other.file_, nullptr);
    path_ = std::move(other.path_);
  }
  return *this;
}

GzLineReader::~GzLineReader() { Close(); }

void GzLineReader::Close() {
  if (file_ != nullptr) {
    gzclose(static_cast<gzFile>(file_));
    file_ = nullptr;
  }
}

Status GzLineReader::Open(const std::string& path) {
  Close();
  path_ = path;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) {
    return NotFound("cannot open file", path);
  }
  gzbuffer(f, 1 << 18);
  file_ = f;
  return Status::Ok();
}

long GzLineReader::FileOffset() const {
  return file_ == nullptr ? 0 : static_cast<long>(gzoffset(static_cast<gzFile>(file_)));
}

bool GzLineReader::ReadLine(std::string& line, Status& status) {
  line.clear();
  if (file_ == nullptr) {
    return false;
  }
  auto* f = static_cast<gzFile>(file_);
  char chunk[8192];
  bool got_any = false;
  while (gzgets(f, chunk, sizeof(chunk)) != nullptr) {
    got_any = true;
    const std::size_t n = std::strlen(chunk);
    if (n > 0 && chunk[n - 1] == '\n') {
      line.append(chunk, n - 1);
      if (!line.empty() && line.back() == '\r') {
        line.pop_back();
      }
      return true;
    }
    line.append(chunk, n);
  }
  int errnum = Z_OK;
  const char* message = gzerror(f, &errnum);
  if (errnum != Z_OK && errnum != Z_BUF_ERROR) {
    status = InvalidInput(std::string("read error: ") + message, path_);
    return false;
  }
  if (errnum == Z_BUF_ERROR) {
    status = InvalidInput("truncated gzip stream", path_);
    return false;
  }
  if (!line.empty() && line.back() == '\r') {
    line.pop_back();
  }
  return got_any;
}

}  // namespace gridslam::io::internal
