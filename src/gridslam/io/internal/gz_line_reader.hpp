// Reads a text file line by line through zlib, so gzip-compressed and plain files are read alike
// (gzopen reads uncompressed files transparently). Internal to io/.
#pragma once

#include <string>

#include "gridslam/common/result.hpp"

namespace gridslam::io::internal {

class GzLineReader {
 public:
  GzLineReader() = default;
  GzLineReader(const GzLineReader&) = delete;
  GzLineReader& operator=(const GzLineReader&) = delete;
  GzLineReader(GzLineReader&& other) noexcept;
  GzLineReader& operator=(GzLineReader&& other) noexcept;
  ~GzLineReader();

  /// Opens `path`; NotFound if it cannot be opened.
  Status Open(const std::string& path);
  /// Reads the next line without its line ending into `line`; false at the end of the file.
  /// NUL bytes stay in the line (so they do not merge lines and shift line numbers). A read
  /// error, or a line longer than kMaxLineBytes, is reported through `status`.
  bool ReadLine(std::string& line, Status& status);
  /// Bytes of the file (compressed bytes for a gzip file) consumed so far, for progress reports.
  [[nodiscard]] long FileOffset() const;

  /// The longest line accepted (64 MiB; a binary file without newlines is an error, not a
  /// whole-file allocation).
  static constexpr std::size_t kMaxLineBytes = std::size_t{1} << 26;

 private:
  void Close();
  bool Fill(Status& status);
  void* file_ = nullptr;  ///< gzFile
  std::string path_;
  std::string buffer_;     ///< Decompressed bytes not yet returned.
  std::size_t begin_ = 0;  ///< First unread byte of buffer_.
  bool eof_ = false;
};

}  // namespace gridslam::io::internal
