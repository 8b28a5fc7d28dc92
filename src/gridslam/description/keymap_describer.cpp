#include "gridslam/description/keymap_describer.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include <opencv2/core.hpp>

#include "gridslam/common/thread_scratch.hpp"
#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/features/surf_feature2d.hpp"
#include "gridslam/grid/log_odds.hpp"

namespace gridslam::description {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

matching::VerificationInput KeyMapDescription::Verification(const KeyMapDescription& a,
                                                            const KeyMapDescription& b) {
  matching::VerificationInput input;
  input.points_b = b.obstacle_points;
  input.distance_a = &a.distance;
  input.points_a = a.obstacle_points;
  input.distance_b = &b.distance;
  return input;
}

KeyMapDescriber::KeyMapDescriber(const DescriptionOptions& options) : options_(options) {
  auto detector = features::CreateDetector(options.detector, options.surf);
  GRIDSLAM_CHECK(detector.ok()) << detector.error().ToString();
  detector_ = detector.value();
}

KeyMapCells KeyMapDescriber::Cells(const keymap::KeyMap& key_map) const {
  return {key_map.log_odds, static_cast<float>(ProbabilityToLogOdds(options_.occupied_probability)),
          static_cast<float>(options_.observed_log_odds)};
}

KeyMapImages KeyMapDescriber::Images(const keymap::KeyMap& key_map) const {
  return Images(Cells(key_map));
}

KeyMapImages KeyMapDescriber::Images(const KeyMapCells& cells) const {
  struct FieldTag {};
  auto& field = ThreadScratch<FieldTag, distance_transform::SquaredDistanceField>();
  SquaredObstacleDistances(cells, field);
  return Images(cells, field, {true, true, true});
}

KeyMapImages KeyMapDescriber::Images(const KeyMapCells& cells,
                                     const distance_transform::SquaredDistanceField& field,
                                     const ImageSelection& selection) const {
  const MapLimits& limits = cells.Limits();
  const int width = limits.Width();
  const int height = limits.Height();
  KeyMapImages images;
  if (selection.obstacle) {
    images.obstacle = ObstacleImage(cells);
  }
  if (selection.grid) {
    images.grid = GridImage(cells);
  }
  // distance_transform::DistanceTransformCells(images.obstacle), from the squared distances.
  if (selection.distance_cells || options_.minmax_normalization) {
    images.distance_cells = cv::Mat(height, width, CV_32F);
    auto* distance_cells = images.distance_cells.ptr<float>();
    for (std::size_t k = 0; k < field.squared.size(); ++k) {
      distance_cells[k] = std::sqrt(field.squared[k]);
    }
  }
  if (options_.minmax_normalization) {
    cv::Mat finite = images.distance_cells.clone();
    cv::patchNaNs(finite, 0.0);
    finite.setTo(0.0F, finite == std::numeric_limits<float>::infinity());
    cv::normalize(finite, images.distance, 0, 255, cv::NORM_MINMAX, CV_8U);
    return images;
  }
  // distance_transform::DistanceToImage(images.distance_cells, clamp): the squared distances are
  // whole numbers, so the pixel of each one below the clamp comes from a table.
  const double clamp_cells = options_.distance_clamp / limits.Resolution();
  const double clamp_squared = std::ceil(clamp_cells * clamp_cells);
  if (clamp_squared > 65536.0) {
    cv::Mat distance_cells = images.distance_cells;
    if (distance_cells.empty()) {
      distance_cells = cv::Mat(height, width, CV_32F);
      auto* d = distance_cells.ptr<float>();
      for (std::size_t k = 0; k < field.squared.size(); ++k) {
        d[k] = std::sqrt(field.squared[k]);
      }
    }
    images.distance = distance_transform::DistanceToImage(distance_cells, clamp_cells);
    return images;
  }
  const auto table_size = static_cast<std::size_t>(clamp_squared) + 1;
  std::vector<std::uint8_t> table(table_size);
  for (std::size_t q = 0; q < table_size; ++q) {
    const double d = std::min(static_cast<double>(std::sqrt(static_cast<float>(q))), clamp_cells);
    table[q] = cv::saturate_cast<std::uint8_t>(d / clamp_cells * 255.0);
  }
  const std::uint8_t beyond = cv::saturate_cast<std::uint8_t>(clamp_cells / clamp_cells * 255.0);
  images.distance = cv::Mat(height, width, CV_8U);
  auto* pixels = images.distance.ptr<std::uint8_t>();
  const auto last = static_cast<float>(table_size - 1);
  // The field's and the table's pointers and the count in locals: a byte store may alias anything,
  // so read through the vectors they were loaded again for every pixel.
  const float* squared = field.squared.data();
  const std::size_t count = field.squared.size();
  const std::uint8_t* pixel_of = table.data();
  for (std::size_t k = 0; k < count; ++k) {
    const float q = squared[k];
    // q <= last <= 65536: a whole number the 32-bit conversion takes exactly.
    pixels[k] =
        q <= last ? pixel_of[static_cast<std::uint32_t>(static_cast<std::int32_t>(q))] : beyond;
  }
  return images;
}

KeyMapDescription KeyMapDescriber::Describe(const keymap::KeyMap& key_map) const {
  auto start = std::chrono::steady_clock::now();
  KeyMapDescription description;
  description.cells = Cells(key_map);
  const MapLimits& limits = description.cells.Limits();
  const double resolution = limits.Resolution();
  // Only the images the options detect and describe on.
  ImageSelection selection;
  selection.grid = options_.detect_image == "grid" || options_.descriptor_image == "grid";
  selection.obstacle = options_.descriptor_image == "obstacle";
  struct FieldTag {};
  auto& field = ThreadScratch<FieldTag, distance_transform::SquaredDistanceField>();
  SquaredObstacleDistances(description.cells, field);
  const KeyMapImages images = Images(description.cells, field, selection);

  // Metric distance field with unobserved cells marked, and the obstacle cell centres.
  KeyMapGeometry geometry = ComputeGeometry(description.cells, field);
  description.distance = std::move(geometry.distance);
  description.obstacle_points = std::move(geometry.obstacle_points);
  description.seconds_distance = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  const cv::Mat& detect_on = options_.detect_image == "grid" ? images.grid : images.distance;
  const cv::Mat& describe_on = options_.descriptor_image == "obstacle" ? images.obstacle
                               : options_.descriptor_image == "grid"   ? images.grid
                                                                       : images.distance;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  // The margin in cells, rounded up to a multiple of SURF's coarsest sampling step so that every
  // octave samples the same pixels as without a margin (the inner keypoints stay the same).
  const int coarsest_step = options_.surf.initial_step << (options_.surf.num_octaves - 1);
  const int margin =
      static_cast<int>(std::ceil(options_.detection_margin / resolution / coarsest_step - 1e-9)) *
      coarsest_step;
  if (margin > 0) {
    cv::Mat padded;
    cv::copyMakeBorder(detect_on, padded, margin, margin, margin, margin, cv::BORDER_REPLICATE);
    detector_->detect(padded, keypoints);
    const auto shift = static_cast<float>(margin);
    const auto max_x = static_cast<float>(detect_on.cols - 1);
    const auto max_y = static_cast<float>(detect_on.rows - 1);
    std::erase_if(keypoints, [&](cv::KeyPoint& kp) {
      kp.pt.x -= shift;
      kp.pt.y -= shift;
      return !(kp.pt.x >= 0.0F && kp.pt.y >= 0.0F && kp.pt.x <= max_x && kp.pt.y <= max_y);
    });
    detector_->compute(describe_on, keypoints, descriptors);
  } else if (const auto* surf = dynamic_cast<const features::SurfFeature2D*>(detector_.get());
             surf != nullptr && &detect_on == &describe_on) {
    surf->DetectThenDescribe(detect_on, keypoints, descriptors);  // one integral image
  } else {
    detector_->detect(detect_on, keypoints);
    detector_->compute(describe_on, keypoints, descriptors);
  }

  matching::FeatureSet& features = description.features;
  features.descriptors = descriptors;
  const bool upright = options_.detector == "usurf";
  const bool has_laplacian = options_.detector == "surf" || options_.detector == "usurf";
  for (const cv::KeyPoint& kp : keypoints) {
    features.points.push_back(limits.Origin() +
                              Eigen::Vector2d(kp.pt.x + 0.5, kp.pt.y + 0.5) * resolution);
    features.scales.push_back(static_cast<double>(kp.size) * resolution);
    if (has_laplacian) {
      features.laplacian_sign.push_back(kp.class_id >= 0 ? 1 : -1);
    }
    if (!upright && kp.angle >= 0.0F) {
      features.angles.push_back(NormalizeAngle(kp.angle * std::numbers::pi / 180.0));
    }
  }
  if (features.angles.size() != features.points.size()) {
    features.angles.clear();
  }
  description.seconds_features = SecondsSince(start);
  return description;
}

}  // namespace gridslam::description
