#include "gridslam/features/synthetic_keymap.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

#include "gridslam/common/check.hpp"

namespace gridslam::features {
namespace {

// A wall from a to b with door gaps of `door` px at random places.
void AddWallWithDoors(std::vector<cv::Vec4f>& walls, cv::Point2f a, cv::Point2f b, int doors,
                      float door, std::mt19937& rng) {
  const float length = static_cast<float>(cv::norm(b - a));
  if (length < 2.0F * door) {
    walls.emplace_back(a.x, a.y, b.x, b.y);
    return;
  }
  std::vector<float> cuts;
  cuts.reserve(static_cast<std::size_t>(doors));
  std::uniform_real_distribution<float> where(door, length - 2.0F * door);
  for (int i = 0; i < doors; ++i) {
    cuts.push_back(where(rng));
  }
  std::sort(cuts.begin(), cuts.end());
  const cv::Point2f dir = (b - a) * (1.0F / length);
  float t = 0.0F;
  for (const float c : cuts) {
    if (c > t) {
      const cv::Point2f p = a + dir * t;
      const cv::Point2f q = a + dir * c;
      walls.emplace_back(p.x, p.y, q.x, q.y);
    }
    t = std::max(t, c + door);
  }
  if (t < length) {
    const cv::Point2f p = a + dir * t;
    walls.emplace_back(p.x, p.y, b.x, b.y);
  }
}

}  // namespace

std::vector<cv::Vec4f> MakeSyntheticWalls(int size, std::uint32_t seed) {
  GRIDSLAM_CHECK(size >= 32) << "size " << size;
  std::mt19937 rng(seed);
  const auto s = static_cast<float>(size);
  std::uniform_real_distribution<float> unit(0.0F, 1.0F);
  std::vector<cv::Vec4f> walls;
  // Rooms: a few vertical and horizontal walls across the floor, each with one or two doors.
  const int nv = 2 + static_cast<int>(rng() % 2);
  const int nh = 2 + static_cast<int>(rng() % 2);
  for (int i = 0; i < nv; ++i) {
    const float x = s * (static_cast<float>(i) + 0.3F + 0.4F * unit(rng)) / static_cast<float>(nv);
    const float y0 = s * 0.1F * unit(rng);
    const float y1 = s * (1.0F - 0.1F * unit(rng));
    AddWallWithDoors(walls, {x, y0}, {x, y1}, 1 + static_cast<int>(rng() % 2), 0.07F * s, rng);
  }
  for (int i = 0; i < nh; ++i) {
    const float y = s * (static_cast<float>(i) + 0.3F + 0.4F * unit(rng)) / static_cast<float>(nh);
    const float x0 = s * 0.1F * unit(rng);
    const float x1 = s * (1.0F - 0.1F * unit(rng));
    AddWallWithDoors(walls, {x0, y}, {x1, y}, 1 + static_cast<int>(rng() % 2), 0.07F * s, rng);
  }
  // Furniture: small boxes, some rotated, and short segments.
  const int boxes = 6 + static_cast<int>(rng() % 5);
  for (int i = 0; i < boxes; ++i) {
    const cv::Point2f c(s * (0.05F + 0.9F * unit(rng)), s * (0.05F + 0.9F * unit(rng)));
    const float w = s * (0.02F + 0.06F * unit(rng));
    const float h = s * (0.02F + 0.04F * unit(rng));
    const float a = unit(rng) < 0.5F ? 0.0F : 3.14159265F * unit(rng);
    const cv::Point2f u(std::cos(a), std::sin(a));
    const cv::Point2f v(-u.y, u.x);
    const cv::Point2f p[4] = {c - u * w - v * h, c + u * w - v * h, c + u * w + v * h,
                              c - u * w + v * h};
    for (int k = 0; k < 4; ++k) {
      walls.emplace_back(p[k].x, p[k].y, p[(k + 1) % 4].x, p[(k + 1) % 4].y);
    }
  }
  const int sticks = 4 + static_cast<int>(rng() % 4);
  for (int i = 0; i < sticks; ++i) {
    const cv::Point2f c(s * unit(rng), s * unit(rng));
    const float a = 3.14159265F * unit(rng);
    const float len = s * (0.03F + 0.08F * unit(rng));
    const cv::Point2f d(std::cos(a) * len, std::sin(a) * len);
    walls.emplace_back(c.x, c.y, c.x + d.x, c.y + d.y);
  }
  return walls;
}

cv::Mat RenderObstacleImage(const std::vector<cv::Vec4f>& walls, int size,
                            const cv::Matx23d& T_image_walls) {
  cv::Mat image(size, size, CV_8UC1, cv::Scalar(255));
  constexpr int kShift = 4;  // sub-pixel end points, 1/16 px
  const auto fixed = [&](double x, double y) {
    const double u = T_image_walls(0, 0) * x + T_image_walls(0, 1) * y + T_image_walls(0, 2);
    const double v = T_image_walls(1, 0) * x + T_image_walls(1, 1) * y + T_image_walls(1, 2);
    return cv::Point(cvRound(u * (1 << kShift)), cvRound(v * (1 << kShift)));
  };
  for (const cv::Vec4f& w : walls) {
    cv::line(image, fixed(w[0], w[1]), fixed(w[2], w[3]), cv::Scalar(0), 1, cv::LINE_8, kShift);
  }
  return image;
}

cv::Mat DistanceImage8U(const cv::Mat& obstacles, double clamp_px) {
  GRIDSLAM_CHECK(obstacles.type() == CV_8UC1 && clamp_px > 0.0) << "bad input";
  cv::Mat distance;
  cv::distanceTransform(obstacles, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::Mat clamped = cv::min(distance, clamp_px);
  cv::Mat image;
  clamped.convertTo(image, CV_8U, 255.0 / clamp_px);
  return image;
}

cv::Mat MakeSyntheticKeyMap(int size, std::uint32_t seed, double clamp_px) {
  return DistanceImage8U(RenderObstacleImage(MakeSyntheticWalls(size, seed), size), clamp_px);
}

}  // namespace gridslam::features
