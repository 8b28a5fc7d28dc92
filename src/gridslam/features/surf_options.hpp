// Options of the project's SURF detector and descriptor (Bay, Ess, Tuytelaars, Van Gool,
// "Speeded-Up Robust Features (SURF)", CVIU 110(3), 2008; docs/method.md §2; docs/design.md §1.4).
// The scale space is the paper's: octave o (0-based) holds the box filters of size L =
// 3·(2^(o+1)·(i+1) + 1), i = 0 .. layers_per_octave−1 (9-15-21-27 / 15-27-39-51 / 27-51-75-99 /
// 51-99-147-195), sampled every initial_step·2^o pixels. Hessian responses are normalised by the
// filter area L² with the image intensities scaled to [0, 1], as OpenSURF does, so
// hessian_threshold has OpenSURF's units (OpenSURF's default is 0.0004). OpenCV normalises each
// lobe by its own area, so its threshold (default 100 on 0–255 images) is not comparable.
#pragma once

#include "gridslam/common/options.hpp"

namespace gridslam::features {

struct SurfOptions {
  /// Minimum det(H_approx) of a keypoint (area-normalised box filters, intensities in [0, 1]);
  /// OpenSURF's default. About 60–100 keypoints on a 300 × 300 synthetic key-map distance image.
  double hessian_threshold = 0.0004;
  /// Octaves of the scale space (the paper uses 4; a fifth continues the pattern: 99, 195, ...).
  int num_octaves = 4;
  /// Filters per octave, >= 3; the paper's 4 give 2 inner layers where maxima are searched.
  int layers_per_octave = 4;
  /// Sampling step of the first octave [px]; it doubles every octave (OpenSURF uses 2).
  int initial_step = 1;
  /// Quadratic fits per candidate (Brown & Lowe 2002): while an offset exceeds half a sample, move
  /// to the neighbouring sample it points to and fit again, at most this many fits; a candidate
  /// still off by more than half a sample is rejected. 1 = OpenSURF's single fit.
  int interpolation_steps = 5;
  /// 128-value descriptor (sums split by the sign of the other response) instead of 64 values.
  bool extended = false;
  /// U-SURF: no orientation assignment, descriptors on the axis-aligned window (angle −1).
  bool upright = false;
  /// Keep at most this many keypoints, the strongest responses first; 0 keeps all.
  int max_features = 0;

  template <class V>
  void Visit(V& v) {
    v("hessian_threshold", hessian_threshold,
      "Minimum det of the area-normalised box-filter Hessian, intensities in [0, 1] [-]");
    v("num_octaves", num_octaves, "Octaves of the scale space (paper: 4)");
    v("layers_per_octave", layers_per_octave, "Box filters per octave, >= 3 (paper: 4)");
    v("initial_step", initial_step, "Sampling step of the first octave, doubling per octave [px]");
    v("interpolation_steps", interpolation_steps,
      "Max sub-pixel fits per candidate (move and refit while an offset > 0.5; 1 = OpenSURF)");
    v("extended", extended, "128-value descriptor instead of 64");
    v("upright", upright, "U-SURF: no orientation, axis-aligned descriptor window");
    v("max_features", max_features, "Keep at most this many strongest keypoints; 0 = all");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(Require(hessian_threshold >= 0.0, "surf.hessian_threshold >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(num_octaves >= 1 && num_octaves <= 6, "surf.num_octaves in [1, 6]"));
    GRIDSLAM_RETURN_IF_ERROR(Require(layers_per_octave >= 3 && layers_per_octave <= 8,
                                     "surf.layers_per_octave in [3, 8]"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(initial_step >= 1 && initial_step <= 4, "surf.initial_step in [1, 4]"));
    GRIDSLAM_RETURN_IF_ERROR(Require(interpolation_steps >= 1 && interpolation_steps <= 10,
                                     "surf.interpolation_steps in [1, 10]"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_features >= 0, "surf.max_features >= 0"));
    return Status::Ok();
  }
};

}  // namespace gridslam::features
