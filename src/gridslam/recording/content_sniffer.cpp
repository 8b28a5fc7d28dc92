#include "gridslam/recording/content_sniffer.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include <zlib.h>

#include "gridslam/recording/internal/bag_container.hpp"

namespace gridslam::recording {
namespace {

constexpr std::size_t kHeadBytes = 64 * 1024;

bool StartsWith(std::span<const std::uint8_t> b, std::string_view magic) {
  return b.size() >= magic.size() &&
         std::equal(magic.begin(), magic.end(), reinterpret_cast<const char*>(b.data()));
}

bool IsNumber(const std::string& token) {
  if (token.empty()) {
    return false;
  }
  char* end = nullptr;
  std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

bool IsIdentifier(const std::string& token) {
  return !token.empty() && std::isupper(static_cast<unsigned char>(token[0])) != 0 &&
         std::all_of(token.begin(), token.end(), [](char c) {
           return std::isupper(static_cast<unsigned char>(c)) != 0 ||
                  std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '_';
         });
}

SniffResult Text(std::string_view text) {
  static const std::set<std::string> kCarmen = {
      "FLASER",    "RLASER",      "LASER3",      "LASER4", "RAWLASER1", "RAWLASER2",    "RAWLASER3",
      "RAWLASER4", "ROBOTLASER1", "ROBOTLASER2", "ODOM",   "PARAM",     "TRUEPOS",      "SYNC",
      "NMEA-GGA",  "NMEA-RMC",    "SONAR",       "BUMPER", "SCANMARK",  "POSITIONLASER"};
  static const std::set<std::string> kG2o = {
      "VERTEX_SE2",  "EDGE_SE2", "VERTEX_SE3:QUAT", "EDGE_SE3:QUAT", "VERTEX_XY",
      "EDGE_SE2_XY", "FIX"};
  static const std::set<std::string> kToro = {"VERTEX2", "EDGE2",   "VERTEX",
                                              "EDGE",    "VERTEX3", "EDGE3"};
  std::istringstream in{std::string(text)};
  std::string line;
  int content_lines = 0;
  int numeric_lines = 0;
  std::size_t numeric_columns = 0;
  bool first_content = true;
  std::string first_word;
  bool all_identifiers = true;
  while (std::getline(in, line) && content_lines < 200) {
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word[0] == '#') {
      continue;
    }
    ++content_lines;
    if (first_content) {
      first_word = word;
      first_content = false;
      if (word == "P2" || word == "P5") {
        return {ContentKind::kNotRecording, "a PGM image"};
      }
      if (word.front() == '{' || word.front() == '[') {
        return {ContentKind::kNotRecording, "a JSON file"};
      }
      if (word == "image:" || word == "resolution:") {
        return {ContentKind::kNotRecording, "a map_server map YAML file"};
      }
    }
    if (kCarmen.contains(word)) {
      return {ContentKind::kCarmenLog, "a CARMEN log"};
    }
    if (kG2o.contains(word)) {
      return {ContentKind::kNotRecording, "a g2o pose graph"};
    }
    if (kToro.contains(word)) {
      return {ContentKind::kNotRecording, "a TORO pose graph"};
    }
    if (IsNumber(word)) {
      std::size_t columns = 1;
      bool numeric = true;
      while (words >> word) {
        ++columns;
        numeric = numeric && IsNumber(word);
      }
      if (numeric) {
        ++numeric_lines;
        numeric_columns = std::max(numeric_columns, columns);
      }
      all_identifiers = false;
    } else if (!IsIdentifier(word)) {
      all_identifiers = false;
    }
  }
  if (content_lines == 0) {
    return {ContentKind::kNotRecording,
            text.empty() ? "an empty file" : "a text file with only comments or blank lines"};
  }
  if (numeric_lines == content_lines) {
    if (numeric_columns == 8) {
      return {ContentKind::kNotRecording,
              "a relations file or a TUM trajectory (lines of 8 numbers)"};
    }
    return {ContentKind::kNotRecording, "a table of numbers (" + std::to_string(numeric_columns) +
                                            " columns), e.g. a trajectory"};
  }
  if (all_identifiers) {
    // Upper-case message names the reader does not know: CARMEN-like, the reader reports them.
    return {ContentKind::kCarmenLog, "a CARMEN-like log"};
  }
  return {ContentKind::kNotRecording,
          "a text file that is not a CARMEN log (first word '" + first_word.substr(0, 40) + "')"};
}

}  // namespace

SniffResult SniffBytes(std::span<const std::uint8_t> head) {
  if (head.empty()) {
    return {ContentKind::kNotRecording, "an empty file"};
  }
  if (StartsWith(head, internal::kRos1Magic)) {
    return {ContentKind::kRos1Bag, "a ROS 1 bag"};
  }
  if (StartsWith(head, "#ROSBAG V")) {
    return {ContentKind::kNotRecording, "a ROS 1 bag of an unsupported version (only 2.0)"};
  }
  if (StartsWith(head, internal::kMcapMagic)) {
    return {ContentKind::kMcap, "an MCAP file"};
  }
  if (StartsWith(head, std::string_view("SQLite format 3\0", 16))) {
    return {ContentKind::kRosbag2, "an SQLite database (rosbag2 .db3?)"};
  }
  if (StartsWith(head, "\x89PNG")) {
    return {ContentKind::kNotRecording, "a PNG image"};
  }
  if (head.size() >= 3 && head[0] == 'P' && (head[1] == '2' || head[1] == '5') &&
      std::isspace(head[2]) != 0) {
    return {ContentKind::kNotRecording, "a PGM image"};
  }
  if (StartsWith(head, "\xFF\xD8\xFF")) {
    return {ContentKind::kNotRecording, "a JPEG image"};
  }
  if (StartsWith(head, "PK\x03\x04")) {
    return {ContentKind::kNotRecording, "a zip archive"};
  }
  if (StartsWith(head, "BZh")) {
    return {ContentKind::kNotRecording, "bzip2-compressed data (decompress it first)"};
  }
  if (StartsWith(head, "\x28\xB5\x2F\xFD")) {
    return {ContentKind::kNotRecording, "zstd-compressed data (decompress it first)"};
  }
  if (StartsWith(head, "\x04\x22\x4D\x18")) {
    return {ContentKind::kNotRecording, "lz4-compressed data (decompress it first)"};
  }
  if (StartsWith(head, "\x1F\x8B")) {
    return {ContentKind::kNotRecording, "gzip-compressed data"};  // SniffPath looks inside
  }
  std::size_t binary = 0;
  for (std::uint8_t c : head) {
    binary += (c == 0 || (c < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\f')) ? 1 : 0;
  }
  if (binary > 0) {
    return {ContentKind::kNotRecording, "binary data"};
  }
  return Text({reinterpret_cast<const char*>(head.data()), head.size()});
}

SniffResult SniffPath(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    for (const auto& entry : fs::directory_iterator(path, ec)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".db3" || ext == ".mcap" || entry.path().filename() == "metadata.yaml") {
        return {ContentKind::kRosbag2, "a rosbag2 folder"};
      }
    }
    return {ContentKind::kNotRecording, "a folder without a rosbag2 recording"};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return {ContentKind::kNotRecording, "a file that cannot be opened"};
  }
  std::vector<std::uint8_t> head(kHeadBytes);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (!StartsWith(head, "\x1F\x8B")) {
    return SniffBytes(head);
  }
  gzFile gz = gzopen(path.c_str(), "rb");
  if (gz == nullptr) {
    return {ContentKind::kNotRecording, "gzip data that cannot be opened"};
  }
  std::vector<std::uint8_t> inner(kHeadBytes);
  const int n = gzread(gz, inner.data(), static_cast<unsigned>(inner.size()));
  gzclose(gz);
  if (n < 0) {
    return {ContentKind::kNotRecording, "corrupt gzip data"};
  }
  inner.resize(static_cast<std::size_t>(n));
  SniffResult r = SniffBytes(inner);
  if (r.kind != ContentKind::kCarmenLog) {
    r.kind = ContentKind::kNotRecording;
    r.description = "gzip-compressed " + r.description;
  }
  return r;
}

}  // namespace gridslam::recording
