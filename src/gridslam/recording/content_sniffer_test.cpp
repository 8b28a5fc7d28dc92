#include "gridslam/recording/content_sniffer.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <zlib.h>

namespace gridslam::recording {
namespace {

SniffResult Sniff(std::string_view text) {
  return SniffBytes({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

void ExpectNot(std::string_view text, const std::string& looks_like) {
  const SniffResult r = Sniff(text);
  EXPECT_EQ(r.kind, ContentKind::kNotRecording) << text;
  EXPECT_NE(r.description.find(looks_like), std::string::npos) << r.description;
}

TEST(ContentSniffer, RecognizesRecordings) {
  EXPECT_EQ(Sniff("# comment\n\nODOM 0 0 0 0 0 0 1.0 host 1.0\n").kind, ContentKind::kCarmenLog);
  EXPECT_EQ(Sniff("RAWLASER1 0 -1.57 3.14 0.01 81.9 0.01 0 2 1 1 0 1.0 h 1.0\n").kind,
            ContentKind::kCarmenLog);
  EXPECT_EQ(Sniff("#ROSBAG V2.0\n\x04").kind, ContentKind::kRos1Bag);
  EXPECT_EQ(Sniff(std::string_view("\x89MCAP0\r\n\x01", 9)).kind, ContentKind::kMcap);
  EXPECT_EQ(Sniff(std::string_view("SQLite format 3\0", 16)).kind, ContentKind::kRosbag2);
}

TEST(ContentSniffer, SaysWhatOtherFilesLookLike) {
  ExpectNot("VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n", "g2o");
  ExpectNot("VERTEX2 0 0 0 0\nEDGE2 0 1 1 0 0 1 0 1 1 0 0\n", "TORO");
  ExpectNot("\x89PNG\r\n\x1a\n", "PNG");
  ExpectNot("P5\n10 10\n255\n", "PGM");
  ExpectNot(std::string_view("P5\n2 2\n255\n\0\0\0\xff", 15), "PGM");
  ExpectNot("", "empty");
  ExpectNot("# only\n# comments\n", "only comments");
  ExpectNot("976052857.1 976052858.2 0.1 0 0 0 0 0.01\n976052859.1 976052860.2 0.1 0 0 0 0 0\n",
            "relations");
  ExpectNot(std::string_view("\x01\x02\x00\x05zzz", 7), "binary");
  ExpectNot("#ROSBAG V1.2\n", "unsupported version");
  ExpectNot("image: map.pgm\nresolution: 0.05\n", "map YAML");
  ExpectNot("hello world, this is prose\n", "not a CARMEN log");
}

TEST(ContentSniffer, LooksInsideGzip) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string log = (dir / "gridslam_sniff_log.gz").string();
  const std::string graph = (dir / "gridslam_sniff_graph.gz").string();
  for (const auto& [path, text] : {std::pair{log, std::string("ODOM 0 0 0 0 0 0 1 h 1\n")},
                                   std::pair{graph, std::string("VERTEX_SE2 0 0 0 0\n")}}) {
    gzFile gz = gzopen(path.c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    gzwrite(gz, text.data(), static_cast<unsigned>(text.size()));
    gzclose(gz);
  }
  EXPECT_EQ(SniffPath(log).kind, ContentKind::kCarmenLog);
  const SniffResult g = SniffPath(graph);
  EXPECT_EQ(g.kind, ContentKind::kNotRecording);
  EXPECT_NE(g.description.find("gzip-compressed a g2o"), std::string::npos) << g.description;
  std::filesystem::remove(log);
  std::filesystem::remove(graph);
}

}  // namespace
}  // namespace gridslam::recording
