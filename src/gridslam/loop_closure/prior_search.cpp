#include "gridslam/loop_closure/prior_search.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gridslam::loop_closure {

Status PriorSearchOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(
      window_per_m >= 0.0 && max_window_xy >= 0.0 && min_window_xy >= 0.0 && window_theta >= 0.0,
      "prior_search windows >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(linear_step > 0.0 && angular_step > 0.0, "prior_search steps > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(truncation > 0.0, "prior_search.truncation > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_points >= 1, "prior_search.max_points >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(min_score >= 0.0 && min_score <= 1.0, "0 <= prior_search.min_score <= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(distinct_distance > 0.0, "prior_search.distinct_distance > 0"));
  return Require(max_ambiguity > 0.0 && max_ambiguity <= 1.0,
                 "0 < prior_search.max_ambiguity <= 1");
}

PriorSearchResult SearchAroundPrior(std::span<const Eigen::Vector2d> points_b,
                                    const Grid2D<float>& distance_a, const Pose2& prior,
                                    double window_xy, const PriorSearchOptions& options) {
  PriorSearchResult result;
  result.T_a_b = prior;
  if (points_b.empty() || distance_a.size() == 0) {
    return result;
  }
  const MapLimits& limits = distance_a.Limits();
  const double res = limits.Resolution();
  const int step = std::max(1, static_cast<int>(std::lround(options.linear_step / res)));
  const int half = static_cast<int>(std::floor(window_xy / (step * res)));
  const int side = 2 * half + 1;
  const int angles =
      2 * static_cast<int>(std::floor(options.window_theta / options.angular_step)) + 1;
  const std::size_t stride =
      std::max<std::size_t>(1, points_b.size() / static_cast<std::size_t>(options.max_points));
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < points_b.size(); k += stride) {
    points.push_back(points_b[k]);
  }
  const int w = limits.Width();
  const int h = limits.Height();
  const float* field = distance_a.data();
  const auto inv_truncation = static_cast<float>(1.0 / options.truncation);
  std::vector<float> scores(static_cast<std::size_t>(angles) * side * side, 0.0F);
  std::vector<int> ci(points.size());
  std::vector<int> cj(points.size());
  for (int a = 0; a < angles; ++a) {
    const double dtheta = (a - angles / 2) * options.angular_step;
    const PointTransform T(prior * Pose2(0.0, 0.0, dtheta));
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector2d c = limits.ToCellCoordinates(T(points[k]));
      ci[k] = static_cast<int>(std::floor(c.x()));
      cj[k] = static_cast<int>(std::floor(c.y()));
    }
    float* slice = scores.data() + static_cast<std::size_t>(a) * side * side;
    for (std::size_t k = 0; k < points.size(); ++k) {
      for (int v = 0; v < side; ++v) {
        const int j = cj[k] + (v - half) * step;
        if (j < 0 || j >= h) {
          continue;
        }
        const float* row = field + static_cast<std::size_t>(j) * static_cast<std::size_t>(w);
        float* out = slice + static_cast<std::size_t>(v) * side;
        for (int u = 0; u < side; ++u) {
          const int i = ci[k] + (u - half) * step;
          if (i < 0 || i >= w) {
            continue;
          }
          const float d = row[i];
          if (d >= 0.0F) {
            out[u] += std::max(0.0F, 1.0F - d * inv_truncation);
          }
        }
      }
    }
  }
  result.poses = static_cast<long>(scores.size());
  const auto best = std::max_element(scores.begin(), scores.end());
  const auto index = static_cast<int>(best - scores.begin());
  const int best_a = index / (side * side);
  const int best_v = (index / side) % side;
  const int best_u = index % side;
  const double n = static_cast<double>(points.size());
  result.score = *best / n;
  const double distinct_cells = options.distinct_distance / (step * res);
  float rival = 0.0F;
  for (int a = 0; a < angles; ++a) {
    for (int v = 0; v < side; ++v) {
      for (int u = 0; u < side; ++u) {
        if (std::hypot(u - best_u, v - best_v) > distinct_cells) {
          rival = std::max(rival, scores[(static_cast<std::size_t>(a) * side + v) * side + u]);
        }
      }
    }
  }
  result.rival = rival / n;
  const double dtheta = (best_a - angles / 2) * options.angular_step;
  result.T_a_b = Pose2((best_u - half) * step * res, (best_v - half) * step * res, 0.0) * prior *
                 Pose2(0.0, 0.0, dtheta);
  result.ok =
      result.score >= options.min_score && result.rival <= options.max_ambiguity * result.score;
  return result;
}

}  // namespace gridslam::loop_closure
