// Fast-Hessian keypoint detector of SURF (Bay et al. 2008, §3; docs/method.md §2.2). The
// Gaussian second derivatives are approximated by box filters evaluated on the integral image:
// Dyy is three stacked lobes (weights +1, −2, +1) of (2l−1) × l pixels, Dxx its transpose, Dxy
// four l × l lobes around a one-pixel cross, for filter size L = 3l. Each response is divided by
// the filter area L² (intensities scaled to [0, 1]) and the blob response is
// det(H_approx) = Dxx·Dyy − (0.9·Dxy)² (Eq. (4)). The scale space is the paper's (§3.3): octave o
// holds L = 3·(2^(o+1)·(i+1) + 1), sampled every initial_step·2^o pixels; keypoints are the
// 3×3×3 maxima above the threshold in the inner layers (ties go to the first in scan order),
// refined by fitting a 3-D quadratic in (x, y, L) (Brown & Lowe 2002): while the offset exceeds
// half a sample the fit moves to the neighbouring sample (at most options.interpolation_steps
// fits; two samples pointing at each other keep the fit clamped to ±0.5), else the candidate is
// rejected. Layers that recur in the next octave are subsampled, not recomputed. The paper's 0.9
// weight matches this normalisation (equal L² for every lobe); it is not OpenCV's per-lobe one.
//
// Keypoint conventions (cv::KeyPoint): pt in pixels with pixel centres at integer coordinates;
// size = the interpolated filter size L [px], so the scale is s = 1.2·L/9 (ScaleOfSize); response
// = det(H_approx) at the extremum; octave = the octave index o (0-based); class_id = sign of the
// Laplacian, sign(Dxx + Dyy): −1 for a bright blob on a dark background, +1 for the reverse;
// angle = −1 (orientation is assigned later, see surf_descriptor.hpp).
#pragma once

#include <vector>

#include <opencv2/core/types.hpp>

#include "gridslam/features/integral_image.hpp"
#include "gridslam/features/surf_options.hpp"

namespace gridslam::features {

/// The 0.9 weight of Dxy in det(H_approx) (Bay et al. 2008, Eq. (4)).
inline constexpr float kDxyWeight = 0.9F;

/// Area-normalised box-filter second derivatives at one pixel and one filter size.
struct BoxHessian {
  float dxx = 0.0F;
  float dyy = 0.0F;
  float dxy = 0.0F;
  [[nodiscard]] float Det() const { return dxx * dyy - kDxyWeight * kDxyWeight * dxy * dxy; }
  [[nodiscard]] float Trace() const { return dxx + dyy; }
};

/// The paper's filter size of layer `layer` in octave `octave` (both 0-based):
/// 3·(2^(octave+1)·(layer+1) + 1), e.g. 9, 15, 21, 27 for octave 0 and 15, 27, 39, 51 for octave 1.
[[nodiscard]] constexpr int FilterSize(int octave, int layer) {
  return 3 * ((2 << octave) * (layer + 1) + 1);
}

/// The SURF scale s (the σ of the Gaussian a filter of this size approximates) of a keypoint size.
[[nodiscard]] constexpr float ScaleOfSize(float size) { return 1.2F * size / 9.0F; }

/// Box-filter Hessian at pixel (x, y) for filter size `filter_size` = 3l with l odd, intensities
/// scaled to [0, 1]. Contract: the filter fits: b <= x < width − b and b <= y < height − b with
/// b = (filter_size − 1) / 2.
[[nodiscard]] BoxHessian ComputeBoxHessian(const IntegralImage& integral, int x, int y,
                                           int filter_size);

/// Detects Fast-Hessian keypoints (conventions above), strongest response first. Positions where
/// a filter does not fit inside the image are not searched. Thread-safe; ignores
/// options.max_features, options.extended and options.upright.
[[nodiscard]] std::vector<cv::KeyPoint> DetectFastHessian(const IntegralImage& integral,
                                                          const SurfOptions& options);

}  // namespace gridslam::features
