#include "gridslam/io/map_io.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "gridslam/io/options_yaml.hpp"
#include "gridslam/testing/data_path.hpp"

namespace gridslam::io {
namespace {

// 3 x 2 cells, origin (-1.5, 2.0): the lower row is free / occupied / unknown, the upper row
// all free except (2, 1) occupied, so a missing row flip shows.
OccupancyImage SmallMap() {
  OccupancyImage map(MapLimits(0.05, {-1.5, 2.0}, 3, 2), kFreeCell);
  map(1, 0) = kOccupiedCell;
  map(2, 0) = kUnknownCell;
  map(2, 1) = kOccupiedCell;
  return map;
}

void ExpectSameMap(const OccupancyImage& a, const OccupancyImage& b) {
  ASSERT_EQ(a.Width(), b.Width());
  ASSERT_EQ(a.Height(), b.Height());
  EXPECT_NEAR(a.Limits().Resolution(), b.Limits().Resolution(), 1e-9);
  EXPECT_TRUE(a.Limits().Origin().isApprox(b.Limits().Origin(), 1e-9));
  EXPECT_EQ(a.Cells(), b.Cells());
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(MapIo, TrinaryValuesAsMapSaver) {
  EXPECT_EQ(TrinaryPixel(0), 254);
  EXPECT_EQ(TrinaryPixel(25), 254);
  EXPECT_EQ(TrinaryPixel(26), 205);
  EXPECT_EQ(TrinaryPixel(64), 205);
  EXPECT_EQ(TrinaryPixel(65), 0);
  EXPECT_EQ(TrinaryPixel(100), 0);
  EXPECT_EQ(TrinaryPixel(-1), 205);
}

TEST(MapIo, PgmIsWrittenExactlyWithTheTopRowFirst) {
  const auto dir = testing::MakeTempDir("map_io_pgm");
  ASSERT_TRUE(WriteMap((dir / "map.yaml").string(), "map.pgm", SmallMap()).ok());
  const std::string pgm = ReadTextFile((dir / "map.pgm").string()).value();
  const std::string header = "P5\n# CREATOR: gridslam 0.050 m/pix\n3 2\n255\n";
  ASSERT_EQ(pgm.size(), header.size() + 6);
  EXPECT_EQ(pgm.substr(0, header.size()), header);
  const std::string pixels = pgm.substr(header.size());
  // Top row (j = 1) first: free free occupied; then j = 0: free occupied unknown.
  EXPECT_EQ(pixels, std::string("\xfe\xfe\x00\xfe\x00\xcd", 6));
  EXPECT_EQ(ReadTextFile((dir / "map.yaml").string()).value(),
            "image: map.pgm\nmode: trinary\nresolution: 0.050000\n"
            "origin: [-1.500000, 2.000000, 0.000000]\nnegate: 0\noccupied_thresh: 0.65\n"
            "free_thresh: 0.196\n\n");
}

TEST(MapIo, PgmAndPngRoundTrips) {
  const auto dir = testing::MakeTempDir("map_io_round_trip");
  for (const std::string image : {"map.pgm", "map.png"}) {
    const std::string yaml = (dir / (image + ".yaml")).string();
    ASSERT_TRUE(WriteMap(yaml, image, SmallMap()).ok());
    const auto read = ReadMap(yaml);
    ASSERT_TRUE(read.ok()) << read.error().ToString();
    ExpectSameMap(read.value(), SmallMap());
  }
}

TEST(MapIo, ReadsAsciiPgmNegateAndScaleModes) {
  const auto dir = testing::MakeTempDir("map_io_modes");
  // P2 with a comment; values 0 (black), 255 (white), 128 (grey, p = 0.498).
  WriteText(dir / "ascii.pgm", "P2\n# a comment\n3 1\n255\n0 255 128\n");
  WriteText(dir / "plain.yaml",
            "image: ascii.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  auto plain = ReadMap((dir / "plain.yaml").string());
  ASSERT_TRUE(plain.ok()) << plain.error().ToString();
  EXPECT_EQ(plain.value()(0, 0), kOccupiedCell);
  EXPECT_EQ(plain.value()(1, 0), kFreeCell);
  EXPECT_EQ(plain.value()(2, 0), kUnknownCell);
  WriteText(dir / "negate.yaml",
            "image: ascii.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 1\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  auto negated = ReadMap((dir / "negate.yaml").string());
  ASSERT_TRUE(negated.ok());
  EXPECT_EQ(negated.value()(0, 0), kFreeCell);
  EXPECT_EQ(negated.value()(1, 0), kOccupiedCell);
  WriteText(dir / "scale.yaml",
            "image: ascii.pgm\nmode: scale\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  auto scaled = ReadMap((dir / "scale.yaml").string());
  ASSERT_TRUE(scaled.ok());
  // ROS 1: 1 + 98 * (0.498 - 0.196) / (0.65 - 0.196) = 66.2 -> 66.
  EXPECT_EQ(scaled.value()(2, 0), 66);
}

TEST(MapIo, ReportsMissingAndMalformedInput) {
  const auto dir = testing::MakeTempDir("map_io_errors");
  EXPECT_EQ(ReadMap((dir / "none.yaml").string()).error().code, ErrorCode::kNotFound);
  WriteText(dir / "no_image.yaml", "resolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(ReadMap((dir / "no_image.yaml").string()).error().code, ErrorCode::kInvalidInput);
  WriteText(dir / "bad.pgm", "P5\n3 2\n255\nab");
  WriteText(dir / "bad.yaml",
            "image: bad.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  EXPECT_EQ(ReadMap((dir / "bad.yaml").string()).error().code, ErrorCode::kInvalidInput);
}

TEST(MapIo, GrayImagesRoundTripWithRowZeroAtTheBottom) {
  const auto dir = testing::MakeTempDir("map_io_gray");
  Grid2D<std::uint8_t> image(MapLimits(0.1, {0.0, 0.0}, 4, 3), 255);
  image(0, 0) = 0;
  image(3, 2) = 100;
  for (const std::string name : {"plan.png", "plan.pgm"}) {
    const std::string path = (dir / name).string();
    ASSERT_TRUE(WriteGrayImage(path, image).ok());
    const auto read = ReadGrayImage(path, 0.1);
    ASSERT_TRUE(read.ok()) << read.error().ToString();
    EXPECT_EQ(read.value().Cells(), image.Cells()) << name;
  }
}

TEST(MapIo, PictureWithPaths) {
  const auto dir = testing::MakeTempDir("map_io_picture");
  const std::string path = (dir / "picture.png").string();
  ASSERT_TRUE(WriteMapPicture(path, SmallMap(), {{{-1.45, 2.02}, {-1.4, 2.07}}}).ok());
  const auto read = ReadGrayImage(path, 0.05);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(read.value().Width(), 3);
}

}  // namespace
}  // namespace gridslam::io
