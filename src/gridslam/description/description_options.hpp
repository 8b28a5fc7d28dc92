// Options of the key-map describer (docs/design.md §1.4; docs/method.md §1.5.1).
#pragma once

#include <string>

#include "gridslam/common/options.hpp"
#include "gridslam/features/surf_options.hpp"

namespace gridslam::description {

struct DescriptionOptions {
  /// Feature detector: surf, usurf, sift, orb or akaze (features::CreateDetector).
  std::string detector = "surf";
  /// Image the keypoints are detected on: "distance" (the paper's distance transform) or
  /// "grid" (the occupancy grid itself: occupied black, free white, unknown grey).
  std::string detect_image = "distance";
  /// Image the descriptors are computed on: "distance", "obstacle" (the binary obstacle image,
  /// as the authors' code does) or "grid".
  std::string descriptor_image = "distance";
  /// Distances are mapped to 8 bits as min(d, clamp) / clamp * 255 [m] (docs/design.md §1.4).
  double distance_clamp = 2.0;
  /// The paper's per-map min-max normalization instead of the fixed clamp.
  bool minmax_normalization = false;
  /// A cell is an obstacle (a source of the distance transform) above this probability [-].
  double occupied_probability = 0.65;
  /// A cell counts as observed (for verification) when |log-odds| exceeds this [-].
  double observed_log_odds = 0.05;
  /// Key maps with fewer features cannot be aligned (paper: 5) [-].
  int min_features = 5;
  /// The detection image is extended by this margin on every side, repeating its edge values,
  /// before detection; keypoints found in the margin are dropped. Without it a detector searches
  /// only where its filters fit inside the image (SURF's octaves: 0.7 / 1.3 / 2.5 / 4.9 m from the
  /// edge at 5 cm cells), so structure near the key map's edge is missed at the larger scales [m].
  double detection_margin = 0.0;
  features::SurfOptions surf;

  template <class V>
  void Visit(V& v) {
    v("detector", detector, "Feature detector: surf, usurf, sift, orb or akaze");
    v("detect_image", detect_image, "Image for keypoint detection: distance or grid");
    v("descriptor_image", descriptor_image,
      "Image for the descriptors: distance, obstacle (binary) or grid");
    v("distance_clamp", distance_clamp, "Distance mapped to white in the 8-bit image [m]");
    v("minmax_normalization", minmax_normalization,
      "Per-map min-max normalization (the paper's) instead of the fixed clamp");
    v("occupied_probability", occupied_probability, "Obstacle cells: probability above this [-]");
    v("observed_log_odds", observed_log_odds, "Observed cells: |log-odds| above this [-]");
    v("min_features", min_features, "Key maps with fewer features are not aligned [-]");
    v("detection_margin", detection_margin,
      "Detection image extended by this margin (edge values repeated); 0 = none [m]");
    v.Section("surf", surf, "SURF detector and descriptor (Bay et al. 2008)");
  }
  [[nodiscard]] Status Validate() const;
};

}  // namespace gridslam::description
