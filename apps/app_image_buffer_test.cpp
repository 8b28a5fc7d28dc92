#include "app_image_buffer.hpp"

#include <gtest/gtest.h>

namespace gridslam::app {
namespace {

TEST(ImageBuffer, ImagesShareTheBufferAndGrowItWhenTooSmall) {
  ImageBuffer buffer;
  EXPECT_EQ(buffer.Bytes(), 0U);
  cv::Mat colour = buffer.Image(300, 200, CV_8UC3);
  ASSERT_EQ(colour.rows, 300);
  ASSERT_EQ(colour.cols, 200);
  ASSERT_EQ(colour.type(), CV_8UC3);
  EXPECT_TRUE(colour.isContinuous());
  colour.setTo(cv::Scalar(1, 2, 3));
  EXPECT_EQ(colour.at<cv::Vec3b>(299, 199), cv::Vec3b(1, 2, 3));
  const std::size_t held = buffer.Bytes();
  EXPECT_GE(held, 300U * 200U * 3U);
  // A smaller image lies on the same pixels; the buffer does not grow.
  const cv::Mat grey = buffer.Image(100, 50, CV_8UC1);
  EXPECT_EQ(grey.data, colour.data);
  EXPECT_EQ(buffer.Bytes(), held);
  // A larger one grows it, and is whole.
  const std::size_t large = held + 1;
  cv::Mat big = buffer.Image(static_cast<int>(large), 1, CV_8UC1);
  EXPECT_GE(buffer.Bytes(), large);
  big.setTo(7);
  EXPECT_EQ(big.at<std::uint8_t>(static_cast<int>(large) - 1, 0), 7);
}

TEST(ImageBuffer, DrawingIntoAHeaderOverItKeepsThePixelsThere) {
  ImageBuffer buffer;
  cv::Mat image = buffer.Image(10, 20, CV_8UC3);
  const std::uint8_t* data = image.data;
  image.create(10, 20, CV_8UC3);  // what RenderQualityImage does with the image it is given
  EXPECT_EQ(image.data, data);
}

}  // namespace
}  // namespace gridslam::app
