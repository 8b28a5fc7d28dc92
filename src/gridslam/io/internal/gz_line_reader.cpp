#include "gridslam/io/internal/gz_line_reader.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

#include <zlib.h>

namespace gridslam::io::internal {

GzLineReader::GzLineReader(GzLineReader&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)),
      path_(std::move(other.path_)),
      buffer_(std::move(other.buffer_)),
      begin_(std::exchange(other.begin_, 0)),
      eof_(other.eof_) {}

GzLineReader& GzLineReader::operator=(GzLineReader&& other) noexcept {
  if (this != &other) {
    Close();
    file_ = std::exchange(other.file_, nullptr);
    path_ = std::move(other.path_);
    buffer_ = std::move(other.buffer_);
    begin_ = std::exchange(other.begin_, 0);
    eof_ = other.eof_;
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

bool GzLineReader::Fill(Status& status) {
  if (eof_ || file_ == nullptr) {
    return false;
  }
  auto* f = static_cast<gzFile>(file_);
  if (begin_ > 0) {
    buffer_.erase(0, begin_);
    begin_ = 0;
  }
  constexpr std::size_t kChunk = 1 << 16;
  const std::size_t size = buffer_.size();
  buffer_.resize(size + kChunk);
  const int n = gzread(f, buffer_.data() + size, static_cast<unsigned>(kChunk));
  buffer_.resize(size + static_cast<std::size_t>(std::max(n, 0)));
  if (n < 0) {
    int errnum = Z_OK;
    const char* message = gzerror(f, &errnum);
    status = InvalidInput(std::string("read error: ") + message, path_);
    return false;
  }
  if (n == 0) {
    eof_ = true;
    int errnum = Z_OK;
    gzerror(f, &errnum);
    if (errnum == Z_BUF_ERROR) {
      status = InvalidInput("truncated gzip stream", path_);
    } else if (errnum != Z_OK) {
      status = InvalidInput("read error", path_);
    }
    return false;
  }
  return true;
}

bool GzLineReader::ReadLine(std::string& line, Status& status) {
  line.clear();
  if (file_ == nullptr) {
    return false;
  }
  std::size_t searched = begin_;
  while (true) {
    const std::size_t newline = buffer_.find('\n', searched);
    if (newline != std::string::npos) {
      line.assign(buffer_, begin_, newline - begin_);
      begin_ = newline + 1;
      break;
    }
    if (buffer_.size() - begin_ > kMaxLineBytes) {
      status = InvalidInput(
          "a line longer than " + std::to_string(kMaxLineBytes >> 20) + " MiB (not a text file?)",
          path_);
      return false;
    }
    const std::size_t scanned = buffer_.size() - begin_;  // bytes of this line without '\n'
    if (!Fill(status)) {
      if (!status.ok()) {
        return false;
      }
      if (begin_ >= buffer_.size()) {
        return false;
      }
      line.assign(buffer_, begin_, std::string::npos);
      begin_ = buffer_.size();
      break;
    }
    searched = begin_ + scanned;  // Fill() may have moved the data to the front
  }
  if (!line.empty() && line.back() == '\r') {
    line.pop_back();
  }
  return true;
}

}  // namespace gridslam::io::internal
