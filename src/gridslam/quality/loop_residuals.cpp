#include "gridslam/quality/loop_residuals.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::quality {
namespace {

double Median(std::vector<double> values) {
  if (values.empty()) {
    return 0.0;
  }
  const auto middle = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) {
    return *middle;
  }
  const double upper = *middle;
  const double lower = *std::max_element(values.begin(), middle);
  return 0.5 * (lower + upper);
}

}  // namespace

LoopResidualStats LoopResiduals(const pose_graph::PoseGraph& graph,
                                const std::vector<LoopMeasurement>& loops) {
  std::vector<double> translations;
  std::vector<double> rotations;
  for (const LoopMeasurement& loop : loops) {
    const int i = graph.IndexOf(loop.from);
    const int j = graph.IndexOf(loop.to);
    if (i < 0 || j < 0) {
      continue;
    }
    const Pose2 estimate = graph.vertex(i).T_map_v.Inverse() * graph.vertex(j).T_map_v;
    const Pose2 residual = loop.T_from_to.Inverse() * estimate;
    translations.push_back(residual.translation().norm());
    rotations.push_back(std::abs(NormalizeAngle(residual.theta())));
  }
  LoopResidualStats stats;
  stats.closures = static_cast<long>(translations.size());
  if (translations.empty()) {
    return stats;
  }
  stats.median_translation = Median(translations);
  stats.max_translation = *std::max_element(translations.begin(), translations.end());
  stats.median_rotation = Median(rotations);
  stats.max_rotation = *std::max_element(rotations.begin(), rotations.end());
  return stats;
}

}  // namespace gridslam::quality
