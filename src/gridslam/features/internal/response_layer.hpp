// Box-filter responses of the Fast-Hessian detector (Bay et al. 2008, §3.1–3.3; docs/method.md
// §2.2) on one octave's sampling grid: det(H_approx) = Dxx·Dyy − (0.9·Dxy)² of one filter size at
// every sample where the filter fits, computed from the integral image with the lobes described in
// fast_hessian.hpp. A layer whose filter size already appeared in the previous octave (the paper's
// octaves overlap: 15 and 27 recur in octave 2, and so on) is taken from it by subsampling.
// Internal to the features module.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "gridslam/features/fast_hessian.hpp"
#include "gridslam/features/integral_image.hpp"

namespace gridslam::features::internal {

/// One filter size: lobe length l = L/3 and half extent b = (L−1)/2.
struct FilterGeometry {
  int size = 0;
  int l = 0;
  int b = 0;
};

/// The geometry of `filter_size`. Contract: filter_size = 3l with l odd >= 3.
[[nodiscard]] FilterGeometry Geometry(int filter_size);

/// Area-normalised box Hessian at pixel (x, y), intensities scaled to [0, 1]. Contract: the
/// filter fits.
[[nodiscard]] BoxHessian HessianAt(const IntegralImage& integral, int x, int y,
                                   const FilterGeometry& filter);

/// Samples a RowCandidates call tests at most.
inline constexpr int kCandidateChunk = 64;

/// The row tests of the scan for local maxima on `count` samples of a row of responses from index
/// k: bit j is set where row[k + j] exceeds `threshold` and row[k + j − 1] and is at least
/// row[k + j + 1] (a 3×3×3 maximum must pass them, ties going to the earlier sample). Vectorised:
/// most samples fail, and a scan of the set bits has no branch per sample to mispredict.
/// Contract: 0 <= count <= kCandidateChunk; row[k − 1] .. row[k + count] readable.
[[nodiscard]] std::uint64_t RowCandidates(const float* row, int k, int count, float threshold);

/// det(H_approx) of one filter size on a grid of nx × ny samples, sample (k, m) at pixel
/// (k·step, m·step). Values are defined only inside [k0, k1] × [m0, m1], where the filter fits;
/// elsewhere the buffer is uninitialised.
class ResponseLayer {
 public:
  [[nodiscard]] const FilterGeometry& filter() const { return filter_; }
  [[nodiscard]] int k0() const { return k0_; }
  [[nodiscard]] int k1() const { return k1_; }
  [[nodiscard]] int m0() const { return m0_; }
  [[nodiscard]] int m1() const { return m1_; }
  /// Response at sample (k, m). Contract: inside the valid range.
  [[nodiscard]] float At(int k, int m) const {
    return det_[static_cast<std::size_t>(m) * static_cast<std::size_t>(nx_) +
                static_cast<std::size_t>(k)];
  }
  /// Row m of the grid, nx() values.
  [[nodiscard]] const float* Row(int m) const {
    return det_.get() + static_cast<std::ptrdiff_t>(m) * nx_;
  }
  [[nodiscard]] int nx() const { return nx_; }

  /// Computes the responses of `filter_size` at sampling step `step` for the whole image.
  void Compute(const IntegralImage& integral, int filter_size, int step);
  /// Takes the responses of `finer` (same filter size, half this step) at every other sample.
  /// Contract: `finer` was computed for an image of the same size at step / 2.
  void Subsample(const ResponseLayer& finer, int width, int height, int step);

 private:
  // Sets the geometry, grid and valid range, and makes room for the grid.
  void Prepare(int filter_size, int width, int height, int step);

  FilterGeometry filter_;
  int step_ = 1;
  int nx_ = 0;
  int ny_ = 0;
  int k0_ = 0;
  int k1_ = -1;
  int m0_ = 0;
  int m1_ = -1;
  std::unique_ptr<float[]> det_;  // NOLINT(modernize-avoid-c-arrays): uninitialised buffer
  std::size_t capacity_ = 0;
};

}  // namespace gridslam::features::internal
