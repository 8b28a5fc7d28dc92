// SURF orientation assignment and descriptor (Bay et al. 2008, §4.1–4.2; docs/method.md
// §2.3–2.5), sampled on the integral image. Orientation: Haar wavelet responses of side 4s at
// the points of a grid of spacing s within radius 6s, weighted by a Gaussian (σ = 2s) centred on
// the keypoint; a window of angular width π/3 slides around the circle of (dx, dy) points (every
// distinct window, not a fixed angular step) and the longest summed vector gives the orientation.
// Descriptor: a 20s square window rotated to that orientation, 4 × 4 sub-regions of 5 × 5 samples
// (spacing s), Haar responses of side 2s along the rotated axes weighted by a Gaussian (σ = 3.3s);
// each sub-region contributes (Σdx, Σdy, Σ|dx|, Σ|dy|) — 64 values — or, extended, Σdx and Σ|dx|
// split by the sign of dy and Σdy and Σ|dy| split by the sign of dx — 128 values; the vector is
// scaled to unit length. Haar responses are computed on the axis-aligned image at the rotated
// sample points (rounded to the nearest pixel boundary) and then rotated, as in the paper. Where a
// wavelet box leaves the image, each half uses the mean of its part inside (no response when a
// half lies wholly outside), which extends the image like a replicated border.
//
// Angles are radians in the image frame (x right, y down), atan2(dy, dx): clockwise on screen,
// like cv::KeyPoint::angle, which stores the same angle in degrees in [0, 360).
#pragma once

#include "gridslam/features/integral_image.hpp"

namespace gridslam::features {

/// Values of the standard and extended SURF descriptors.
inline constexpr int kSurfDescriptorSize = 64;
inline constexpr int kSurfExtendedDescriptorSize = 128;

/// Dominant orientation [rad, in (−π, π]] of the keypoint at (x, y) [px] with scale s =
/// ScaleOfSize(size) > 0; 0 where all wavelet responses vanish. Thread-safe.
[[nodiscard]] float AssignOrientation(const IntegralImage& integral, float x, float y, float scale);

/// Writes the SURF descriptor (64 values, or 128 if `extended`) of the keypoint at (x, y) [px]
/// with scale s > 0 and orientation `angle` [rad] (0 for U-SURF) to `out`. The result has unit L2
/// norm unless every response is zero (then all zeros). Thread-safe.
void ComputeSurfDescriptor(const IntegralImage& integral, float x, float y, float scale,
                           float angle, bool extended, float* out);

}  // namespace gridslam::features
