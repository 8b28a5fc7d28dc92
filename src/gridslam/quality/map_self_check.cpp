#include "gridslam/quality/map_self_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/grid/scan_points.hpp"

namespace gridslam::quality {

double SelfCheckStats::Score() const {
  return returns > 0 ? static_cast<double>(agreeing) / static_cast<double>(returns) : 1.0;
}

double SelfCheckStats::Contradiction() const {
  return returns > 0 ? static_cast<double>(contradicting) / static_cast<double>(returns) : 0.0;
}

double SelfCheckStats::MeanDistance() const {
  return returns > 0 ? distance_sum / static_cast<double>(returns) : 0.0;
}

bool SelfCheckStats::Suspect(const SelfCheckOptions& options) const {
  return Score() < options.suspect_below;
}

void SelfCheckStats::Merge(const SelfCheckStats& other) {
  scans += other.scans;
  returns += other.returns;
  agreeing += other.agreeing;
  contradicting += other.contradicting;
  outside += other.outside;
  distance_sum += other.distance_sum;
}

namespace {

// Distance [m] from every cell to the nearest cell where `source(value)` holds; exact up to
// `max_distance` [m], +inf (or exact) beyond.
template <class Predicate>
Grid2D<float> DistanceTo(const OccupancyImage& map, Predicate source, double max_distance) {
  const MapLimits& limits = map.Limits();
  std::vector<std::uint8_t> is_source(map.size());
  for (std::size_t k = 0; k < map.size(); ++k) {
    is_source[k] = source(map.data()[k]) ? 1 : 0;
  }
  distance_transform::SquaredDistanceField field;
  const auto max_cells = static_cast<float>(max_distance / limits.Resolution() + 2.0);
  distance_transform::SquaredEuclideanDistanceTransform(is_source.data(), limits.Width(),
                                                        limits.Height(), field, false, max_cells);
  Grid2D<float> out(limits, distance_transform::kInfinity);
  const auto resolution = static_cast<float>(limits.Resolution());
  for (std::size_t k = 0; k < field.squared.size(); ++k) {
    out.data()[k] = std::sqrt(field.squared[k]) * resolution;
  }
  return out;
}

}  // namespace

SelfCheckResult CheckMap(const Grid2D<float>& log_odds, const std::vector<fusion::PosedScan>& scans,
                         const fusion::FusionOptions& fusion, const SelfCheckOptions& options) {
  SelfCheckResult result;
  const OccupancyImage map = fusion::ToOccupancy(log_odds, fusion);
  const MapLimits& limits = map.Limits();
  result.returns_per_cell = Grid2D<float>(limits, 0.0F);
  result.disagreeing_per_cell = Grid2D<float>(limits, 0.0F);
  const Grid2D<float> to_occupied = DistanceTo(
      map, [](signed char v) { return v == kOccupiedCell; }, options.distance_clamp);
  const Grid2D<float> to_not_free = DistanceTo(
      map, [](signed char v) { return v != kFreeCell; }, options.agreement_distance);
  // Cell-centre distances are multiples of the resolution: a small slack keeps "within 2 cells"
  // exact at agreement_distance = 2 * resolution.
  const double agree = options.agreement_distance + 1e-6;
  SelfCheckStats& stats = result.stats;
  const Pose2* last = nullptr;
  for (const fusion::PosedScan& s : scans) {
    if (s.scan == nullptr) {
      continue;
    }
    if (last != nullptr &&
        (s.T_map_base.translation() - last->translation()).norm() < options.min_motion &&
        std::abs(NormalizeAngle(s.T_map_base.theta() - last->theta())) < options.min_rotation) {
      continue;
    }
    last = &s.T_map_base;
    ++stats.scans;
    const ScanPoints points = ExtractScanPoints(*s.scan, s.T_base_laser, options.max_range);
    for (const Eigen::Vector2d& q : points.points) {
      const Eigen::Array2i cell = limits.CellIndex(s.T_map_base * q);
      if (!limits.Contains(cell)) {
        ++stats.outside;
        continue;
      }
      ++stats.returns;
      result.returns_per_cell.at(cell) += 1.0F;
      const double d = to_occupied.at(cell);
      stats.distance_sum += std::min(d, options.distance_clamp);
      if (d <= agree) {
        ++stats.agreeing;
      } else {
        result.disagreeing_per_cell.at(cell) += 1.0F;
      }
      if (to_not_free.at(cell) > agree) {
        ++stats.contradicting;
      }
    }
  }
  return result;
}

}  // namespace gridslam::quality
