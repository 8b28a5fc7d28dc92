#include "gridslam/description/description_options.hpp"

#include "gridslam/features/surf_feature2d.hpp"

namespace gridslam::description {

Status DescriptionOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(features::CreateDetector(detector, surf).status());
  GRIDSLAM_RETURN_IF_ERROR(Require(detect_image == "distance" || detect_image == "grid",
                                   "description.detect_image is distance or grid"));
  GRIDSLAM_RETURN_IF_ERROR(Require(descriptor_image == "distance" ||
                                       descriptor_image == "obstacle" || descriptor_image == "grid",
                                   "description.descriptor_image is distance, obstacle or grid"));
  GRIDSLAM_RETURN_IF_ERROR(Require(distance_clamp > 0.0, "description.distance_clamp > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(occupied_probability > 0.5 && occupied_probability < 1.0,
                                   "description.occupied_probability in (0.5, 1)"));
  GRIDSLAM_RETURN_IF_ERROR(Require(observed_log_odds >= 0.0, "description.observed_log_odds >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(min_features >= 0, "description.min_features >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(detection_margin >= 0.0, "description.detection_margin >= 0"));
  return surf.Validate();
}

}  // namespace gridslam::description
