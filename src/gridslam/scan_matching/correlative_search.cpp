#include "gridslam/scan_matching/correlative_search.hpp"

#include <cmath>
#include <vector>

namespace gridslam::scan_matching {

SearchResult CorrelativeSearch(const MatchingField& field, const ScanPoints& scan,
                               const Pose2& centre, const ScanMatcherOptions& options,
                               std::size_t max_points) {
  SearchResult best;
  best.T_odom_base = centre;
  const MapLimits& limits = field.Limits();
  const double res = limits.Resolution();
  const int w = limits.Width();
  const int h = limits.Height();
  if (scan.points.empty() || w == 0 || h == 0) {
    return best;
  }
  // Gaussian score by squared distance in cells^2 (an integer below the truncation radius).
  const auto max_sq =
      static_cast<int>(std::ceil(field.MaxDistance() / res) * std::ceil(field.MaxDistance() / res));
  std::vector<float> table(static_cast<std::size_t>(max_sq) + 2);
  for (std::size_t k = 0; k < table.size(); ++k) {
    const double d2 = static_cast<double>(k) * res * res;
    table[k] =
        static_cast<float>(std::exp(-0.5 * d2 / (options.search_sigma * options.search_sigma)));
  }
  auto score_of = [&](std::size_t index) {
    const float sq = field.SquaredDistanceCells(index);
    return sq <= static_cast<float>(max_sq) ? table[static_cast<std::size_t>(sq)] : 0.0F;
  };
  const std::size_t stride =
      std::max<std::size_t>(1, (scan.points.size() + max_points - 1) / max_points);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < scan.points.size(); k += stride) {
    points.push_back(scan.points[k]);
  }
  const int linear_cells = static_cast<int>(std::floor(options.search_linear_window / res /
                                                       options.search_linear_step)) *
                           options.search_linear_step;
  const int angular_steps =
      static_cast<int>(std::floor(options.search_angular_window / options.search_angular_step));
  std::vector<Eigen::Array2i> cells(points.size());
  double best_score = -1.0;
  for (int a = -angular_steps; a <= angular_steps; ++a) {
    const double theta = centre.theta() + a * options.search_angular_step;
    const Pose2 rotated(centre.translation(), theta);
    for (std::size_t k = 0; k < points.size(); ++k) {
      cells[k] = limits.CellIndex(rotated * points[k]);
    }
    for (int dj = -linear_cells; dj <= linear_cells; dj += options.search_linear_step) {
      for (int di = -linear_cells; di <= linear_cells; di += options.search_linear_step) {
        float sum = 0.0F;
        for (const Eigen::Array2i& cell : cells) {
          const int i = cell.x() + di;
          const int j = cell.y() + dj;
          if (i >= 0 && j >= 0 && i < w && j < h) {
            sum += score_of(static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
                            static_cast<std::size_t>(i));
          }
        }
        ++best.evaluated;
        // Prefer the lattice pose nearest the centre among equal scores.
        const double score = sum - 1e-6 * (std::abs(a) + std::abs(di) + std::abs(dj));
        if (score > best_score) {
          best_score = score;
          best.score = sum / static_cast<double>(points.size());
          best.T_odom_base = Pose2(centre.translation() + Eigen::Vector2d(di, dj) * res, theta);
        }
      }
    }
  }
  return best;
}

}  // namespace gridslam::scan_matching
