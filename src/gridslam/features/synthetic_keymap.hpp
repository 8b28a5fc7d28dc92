// Synthetic key-map images for the SURF tests and benchmarks: a random office-like floor of wall
// segments (walls with door gaps, furniture, pillars), drawn 1 px wide into a binary obstacle
// image (obstacles 0, everything else 255, docs/design.md §1.4) and turned into the 8-bit distance
// image the description uses: min(d, clamp) / clamp · 255 of the exact Euclidean distance d to the
// nearest obstacle (cv::distanceTransform, DIST_L2, DIST_MASK_PRECISE). Deterministic per seed.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace gridslam::features {

/// Wall segments (x0, y0, x1, y1) [px] of a random floor filling a size × size image.
[[nodiscard]] std::vector<cv::Vec4f> MakeSyntheticWalls(int size, std::uint32_t seed);

/// Binary obstacle image (obstacles 0, free 255) of size × size with the walls mapped by the affine
/// map `T_image_walls` (pixel coordinates, pixel centres at integers) drawn 1 px wide.
[[nodiscard]] cv::Mat RenderObstacleImage(const std::vector<cv::Vec4f>& walls, int size,
                                          const cv::Matx23d& T_image_walls = {1, 0, 0, 0, 1, 0});

/// 8-bit distance image of a binary obstacle image: min(d, clamp_px) / clamp_px · 255.
/// Contract: obstacles is CV_8UC1, clamp_px > 0.
[[nodiscard]] cv::Mat DistanceImage8U(const cv::Mat& obstacles, double clamp_px);

/// DistanceImage8U(RenderObstacleImage(MakeSyntheticWalls(size, seed), size), clamp_px).
[[nodiscard]] cv::Mat MakeSyntheticKeyMap(int size, std::uint32_t seed, double clamp_px = 30.0);

}  // namespace gridslam::features
