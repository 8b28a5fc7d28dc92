#include "gridslam/loop_closure/free_space_check.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::loop_closure {

Status FreeSpaceCheckOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(
      Require(agreement_distance > 0.0, "loop_closure.free_space_check.agreement_distance > 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(!baseline_travel.empty(), "loop_closure.free_space_check.baseline_travel not empty"));
  for (const double travel : baseline_travel) {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(travel > 0.0, "loop_closure.free_space_check.baseline_travel > 0"));
  }
  return Require(max_ratio >= 1.0 && min_excess >= 0.0,
                 "loop_closure.free_space_check.max_ratio >= 1, min_excess >= 0");
}

double FreeSpaceCounts::Contradiction() const {
  return observed > 0 ? static_cast<double>(contradicting) / static_cast<double>(observed) : 0.0;
}

void FreeSpaceCounts::Merge(const FreeSpaceCounts& other) {
  returns += other.returns;
  observed += other.observed;
  agreeing += other.agreeing;
  contradicting += other.contradicting;
}

FreeSpaceCounts ReplayReturns(std::span<const Eigen::Vector2d> points, const Pose2& T_cells_p,
                              const description::KeyMapCells& cells, double agreement_distance) {
  FreeSpaceCounts counts;
  const MapLimits& limits = cells.Limits();
  if (limits.NumCells() == 0) {
    counts.returns = static_cast<long>(points.size());
    return counts;
  }
  const int radius = static_cast<int>(std::ceil(agreement_distance / limits.Resolution()));
  for (const Eigen::Vector2d& point : points) {
    ++counts.returns;
    const Eigen::Array2i c = limits.CellIndex(T_cells_p * point);
    if (!limits.Contains(c) || !cells.Observed(c.x(), c.y())) {
      continue;
    }
    ++counts.observed;
    bool all_observed = true;
    bool agrees = false;
    for (int dj = -radius; dj <= radius && !agrees; ++dj) {
      for (int di = -radius; di <= radius; ++di) {
        if (di * di + dj * dj > radius * radius) {
          continue;
        }
        const Eigen::Array2i n(c.x() + di, c.y() + dj);
        if (!limits.Contains(n)) {
          all_observed = false;
        } else if (cells.Obstacle(n.x(), n.y())) {
          agrees = true;
          break;
        } else {
          all_observed = all_observed && cells.Observed(n.x(), n.y());
        }
      }
    }
    counts.agreeing += agrees ? 1 : 0;
    counts.contradicting += !agrees && all_observed ? 1 : 0;
  }
  return counts;
}

FreeSpaceCounts ReplayPair(std::span<const Eigen::Vector2d> points_a,
                           const description::KeyMapCells& cells_a,
                           std::span<const Eigen::Vector2d> points_b,
                           const description::KeyMapCells& cells_b, const Pose2& T_a_b,
                           double agreement_distance) {
  FreeSpaceCounts counts = ReplayReturns(points_b, T_a_b, cells_a, agreement_distance);
  counts.Merge(ReplayReturns(points_a, T_a_b.Inverse(), cells_b, agreement_distance));
  return counts;
}

namespace {

double Median(std::vector<double>& values) {
  if (values.empty()) {
    return 0.0;
  }
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

FreeSpaceVerdict JudgeContradictions(std::vector<double> alignments, std::vector<double> baselines,
                                     const FreeSpaceCheckOptions& options) {
  FreeSpaceVerdict verdict;
  verdict.alignments = Median(alignments);
  verdict.baseline = Median(baselines);
  verdict.refused = options.enabled && !alignments.empty() &&
                    verdict.alignments > options.max_ratio * verdict.baseline + options.min_excess;
  return verdict;
}

}  // namespace gridslam::loop_closure
