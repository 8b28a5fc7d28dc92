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
  /// A read error is reported through `status`.
  bool ReadLine(std::string& line, Status& status);
  /// Bytes of the file (compressed bytes for a gzip file) consumed so far, for progress reports.
  [[nodiscard]] long FileOffset() const;

 private:
  void Close();
  void* file_ = nullptr;  ///< gzFile
  std::string path_;
};

}  // namespace gridslam::io::internal
