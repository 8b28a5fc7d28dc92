// Exact Euclidean distance transform of a binary grid after Felzenszwalb & Huttenlocher,
// "Distance transforms of sampled functions", Theory of Computing 8(19):415-428, 2012
// (docs/method.md §3). The squared distance D(p) = min_q |p - q|^2 over source cells q is
// separable: a pass along every column (distance to the nearest source in the column, two linear
// scans since the input is binary) followed by the 1-D lower envelope of parabolas along every row.
// O(cells), exact, and it also yields the nearest source of every cell (the "label" / Voronoi map)
// that the scan matcher uses for correspondences. In the gridslam pipeline the sources are obstacle
// cells (docs/design.md §1.4): free and unknown cells are not sources. OpenCV's DIST_MASK_PRECISE
// computes the same distances (bench/bench_distance_transform.cpp compares the two).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "gridslam/grid/grid2d.hpp"

namespace gridslam::distance_transform {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Output of the 2-D transform, row-major like Grid2D (index j * width + i).
struct SquaredDistanceField {
  int width = 0;
  int height = 0;
  std::vector<float> squared;  ///< Squared distance to the nearest source [cells^2]; +inf if none.
  std::vector<int32_t> nearest;  ///< Linear index of the nearest source; -1 if none (optional).
};

/// 1-D squared distance transform of the sampled function `f` (n samples; samples that are not
/// finite are not sources): d[q] = min_p (q - p)^2 + f[p], and arg[q] the minimizing p (-1 and
/// d = +inf when no sample is finite). `arg` may be null. Scratch space is allocated by the caller:
/// `v` holds n ints, `z` n + 1 floats. Ties resolve to the lower index.
void SquaredDistance1D(const float* f, int n, float* d, int32_t* arg, int32_t* v, float* z);

/// Exact squared Euclidean distance transform of a binary grid of `width` x `height` cells,
/// row-major: `is_source[j * width + i] != 0` marks a source. Distances greater than
/// `max_distance` cells may be reported as +inf (with label -1), which makes sparse grids cheaper;
/// every distance at or below it is exact. Fills `out` (reusing its storage); labels only if
/// `with_nearest`.
void SquaredEuclideanDistanceTransform(const std::uint8_t* is_source, int width, int height,
                                       SquaredDistanceField& out, bool with_nearest = false,
                                       float max_distance = kInfinity);

/// Rows [row0, row1) of SquaredEuclideanDistanceTransform (0 <= row0 <= row1 <= height): the
/// same distances and labels (labels index the whole grid), `out` holding row1 - row0 rows of
/// `width` cells. The row pass runs on those rows alone (a field updating a region from the
/// sources around it needs the region's rows only).
void SquaredEuclideanDistanceTransformRows(const std::uint8_t* is_source, int width, int height,
                                           int row0, int row1, SquaredDistanceField& out,
                                           bool with_nearest = false,
                                           float max_distance = kInfinity);

/// The same transform with the float lower envelope of SquaredDistance1D on every row (F&H): what
/// SquaredEuclideanDistanceTransform computes with integers on grids up to 4096 cells a side
/// (the same distances and labels, tested), and uses beyond.
void SquaredEuclideanDistanceTransformFloat(const std::uint8_t* is_source, int width, int height,
                                            SquaredDistanceField& out, bool with_nearest = false,
                                            float max_distance = kInfinity);

/// Euclidean distance in cells from every pixel of an 8-bit single-channel image to its nearest
/// ZERO pixel (OpenCV's convention: zero pixels are the obstacles). Returns CV_32F; +inf when the
/// image has no zero pixel.
cv::Mat DistanceTransformCells(const cv::Mat& image);

/// Euclidean distance in metres from every cell to the nearest cell where `is_source` is non-zero,
/// with the same MapLimits; +inf where there is no source.
Grid2D<float> DistanceTransformMetres(const Grid2D<std::uint8_t>& is_source);

/// Maps distances to 8 bits with a fixed clamp (docs/design.md §1.4): min(d, d_max) / d_max * 255,
/// d and d_max in the same unit. d_max > 0.
cv::Mat DistanceToImage(const cv::Mat& distance, double d_max);

}  // namespace gridslam::distance_transform
