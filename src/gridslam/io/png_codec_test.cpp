#include "gridslam/io/png_codec.hpp"

#include <random>

#include <gtest/gtest.h>

namespace gridslam::io {
namespace {

cv::Mat RandomImage(int rows, int cols, int type, unsigned seed) {
  cv::Mat image(rows, cols, type);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int r = 0; r < rows; ++r) {
    std::uint8_t* row = image.ptr<std::uint8_t>(r);
    for (std::size_t i = 0; i < static_cast<std::size_t>(cols) * image.elemSize(); ++i) {
      row[i] = static_cast<std::uint8_t>(byte(random));
    }
  }
  return image;
}

// What OpenCV's decoder reads back from our encoder is the image, bit for bit.
cv::Mat RoundTrip(const cv::Mat& image, int threads = 1) {
  const auto png = EncodePng(image, threads);
  EXPECT_TRUE(png.ok());
  if (!png.ok()) {
    return {};
  }
  const std::vector<std::uint8_t> bytes(png.value().begin(), png.value().end());
  auto decoded = DecodeImage(bytes, "test.png");
  EXPECT_TRUE(decoded.ok()) << (decoded.ok() ? "" : decoded.error().ToString());
  return decoded.ok() ? decoded.value() : cv::Mat();
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(PngCodec, GreyBgrAndBgraImagesDecodeToThemselves) {
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat image = RandomImage(17, 23, type, 5U + static_cast<unsigned>(type));
    EXPECT_TRUE(Same(RoundTrip(image), image)) << "type " << type;
  }
}

TEST(PngCodec, OnePixelAndOneRowImages) {
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(40, 1), cv::Size(1, 40)}) {
    const cv::Mat image = RandomImage(size.height, size.width, CV_8UC3, 11U);
    EXPECT_TRUE(Same(RoundTrip(image), image)) << size;
  }
}

TEST(PngCodec, ARegionOfALargerImageIsWrittenWithItsOwnRows) {
  const cv::Mat whole = RandomImage(30, 40, CV_8UC3, 3U);
  const cv::Mat region = whole(cv::Rect(5, 7, 20, 10));  // rows not contiguous
  ASSERT_FALSE(region.isContinuous());
  EXPECT_TRUE(Same(RoundTrip(region), region.clone()));
}

TEST(PngCodec, DataBeyondOneChunkSpansSeveralIdatChunks) {
  // Noise does not compress: about 9 MB of image data, more than one 8 MiB IDAT chunk.
  const cv::Mat image = RandomImage(1000, 3000, CV_8UC3, 7U);
  const auto png = EncodePng(image);
  ASSERT_TRUE(png.ok());
  std::size_t chunks = 0;
  for (std::size_t at = png.value().find("IDAT"); at != std::string::npos;
       at = png.value().find("IDAT", at + 4)) {
    ++chunks;
  }
  EXPECT_GE(chunks, 2U);
  EXPECT_TRUE(Same(RoundTrip(image), image));
}

TEST(PngCodec, LargeImagesCompressedInBandsDecodeToThemselves) {
  // A map-like picture of 9.6 MB: flat areas, edges and noise, so that every band compresses to
  // something different and the bands' joins and combined check value are exercised.
  cv::Mat image = RandomImage(1600, 2000, CV_8UC3, 9U);
  image(cv::Rect(0, 0, 2000, 700)).setTo(cv::Scalar(205, 205, 205));
  image(cv::Rect(300, 900, 1200, 300)).setTo(cv::Scalar(0, 0, 255));
  const auto one = EncodePng(image, 1);
  const auto two = EncodePng(image, 2);
  ASSERT_TRUE(one.ok() && two.ok());
  EXPECT_NE(one.value(), two.value()) << "two threads should have deflated two bands";
  for (const int threads : {1, 2, 3}) {
    EXPECT_TRUE(Same(RoundTrip(image, threads), image)) << threads << " threads";
  }
  const cv::Mat grey = RandomImage(3000, 3000, CV_8UC1, 13U);
  EXPECT_TRUE(Same(RoundTrip(grey, 2), grey));
}

TEST(PngCodec, SmallImagesAreOneStreamWhateverTheThreads) {
  const cv::Mat image = RandomImage(100, 200, CV_8UC3, 17U);
  EXPECT_EQ(EncodePng(image, 1).value(), EncodePng(image, 4).value());
}

TEST(PngCodec, ImagesPngCannotHoldAreRefused) {
  EXPECT_FALSE(EncodePng(cv::Mat()).ok());
  EXPECT_FALSE(EncodePng(cv::Mat(4, 4, CV_16UC1, cv::Scalar(0))).ok());
  EXPECT_FALSE(EncodePng(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0))).ok());
  EXPECT_FALSE(EncodePng(cv::Mat(4, 4, CV_8UC2, cv::Scalar(0))).ok());
}

TEST(PngCodec, BytesThatAreNoImageAreBadInput) {
  const std::string text = "\x89PNG\r\n\x1a\n but nothing after the signature";
  const auto decoded =
      DecodeImage(std::vector<std::uint8_t>(text.begin(), text.end()), "broken.png");
  ASSERT_FALSE(decoded.ok());
  EXPECT_EQ(decoded.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(decoded.error().file, "broken.png");
}

}  // namespace
}  // namespace gridslam::io
