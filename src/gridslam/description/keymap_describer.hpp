// Key-map description (docs/design.md §1.4; docs/method.md §1.5.1): the distance transform of a
// key map's grid (distance to the nearest obstacle) is treated as an image and SURF keypoints and
// descriptors are taken from it; the keypoints are converted to metres in the key map's own frame
// at once, so every later step (matching/align.hpp) works in metres. The describer also keeps
// what the grid verification needs: the metric distance field (unknown cells marked) and the
// obstacle cell centres.
//
// Image convention: pixel (u, v) = grid cell (i, j), so image rows grow with +y. The image is the
// mirror of how a map is usually drawn, which does not matter for matching (every key map uses
// the same mapping) and makes an image angle atan2(dv, du) equal to the angle in the key map's
// frame, counter-clockwise from +x.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <opencv2/features2d.hpp>

#include "gridslam/description/description_options.hpp"
#include "gridslam/description/key_map_cells.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/keymap/key_map.hpp"
#include "gridslam/matching/feature_set.hpp"
#include "gridslam/matching/grid_verification.hpp"

namespace gridslam::description {

/// Everything later stages need of one key map; frame = the key map's frame.
struct KeyMapDescription {
  matching::FeatureSet features;
  /// Distance to the nearest obstacle [m]; matching::kUnknownDistance on unobserved cells.
  Grid2D<float> distance;
  /// Centres of the obstacle cells [m].
  std::vector<Eigen::Vector2d> obstacle_points;
  /// The two bits per cell that `distance` and `obstacle_points` follow from (ComputeGeometry).
  KeyMapCells cells;
  double seconds_distance = 0.0;  ///< Time of the distance transform and images [s].
  double seconds_features = 0.0;  ///< Time of detection and description [s].

  /// The verification input of aligning `b` to `a` (borrows both; they must outlive it).
  static matching::VerificationInput Verification(const KeyMapDescription& a,
                                                  const KeyMapDescription& b);
};

/// The 8-bit images of a key map (for people and for the detectors).
struct KeyMapImages {
  cv::Mat distance;        ///< Clamped distance image, CV_8U (obstacles black).
  cv::Mat obstacle;        ///< Binary obstacle image, CV_8U: obstacles 0, the rest 255.
  cv::Mat grid;            ///< Occupancy image, CV_8U: occupied 0, free 255, unknown 128.
  cv::Mat distance_cells;  ///< Distance to the nearest obstacle [cells], CV_32F (+inf if none).
};

class KeyMapDescriber {
 public:
  /// Contract: options.Validate() is ok.
  explicit KeyMapDescriber(const DescriptionOptions& options);

  /// Describes one key map. Deterministic; thread-safe (the detector is immutable).
  [[nodiscard]] KeyMapDescription Describe(const keymap::KeyMap& key_map) const;
  /// The images Describe() works on.
  [[nodiscard]] KeyMapImages Images(const keymap::KeyMap& key_map) const;
  [[nodiscard]] KeyMapImages Images(const KeyMapCells& cells) const;
  /// The obstacle and observed cells of the key map (thresholds of the options).
  [[nodiscard]] KeyMapCells Cells(const keymap::KeyMap& key_map) const;
  [[nodiscard]] const DescriptionOptions& Options() const { return options_; }

 private:
  /// Which images Images() makes besides the 8-bit distance image.
  struct ImageSelection {
    bool grid = false;
    bool obstacle = false;
    bool distance_cells = false;
  };
  /// The selected images of `cells` from its squared obstacle distances
  /// (SquaredObstacleDistances).
  [[nodiscard]] KeyMapImages Images(const KeyMapCells& cells,
                                    const distance_transform::SquaredDistanceField& field,
                                    const ImageSelection& selection) const;

  DescriptionOptions options_;
  cv::Ptr<cv::Feature2D> detector_;
};

}  // namespace gridslam::description
