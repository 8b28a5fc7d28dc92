#include "gridslam/scan_matching/correlative_search.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gridslam/common/angles.hpp"

namespace gridslam::scan_matching {
namespace {

// Scores every pose of `lattice` around `centre`; `visit(score_sum, a, di, dj, theta)` sees each.
template <class Visit>
long ScoreLattice(const MatchingField& field, const ScanPoints& scan, const Pose2& centre,
                  const SearchLattice& lattice, std::size_t* num_points, Visit&& visit) {
  const MapLimits& limits = field.Limits();
  const RingLayout& layout = field.Layout();
  const double res = limits.Resolution();
  const int w = limits.Width();
  const int h = limits.Height();
  *num_points = 0;
  if (scan.points.empty() || w == 0 || h == 0) {
    return 0;
  }
  // Gaussian score by squared distance in cells^2 (an integer below the truncation radius).
  const auto max_sq =
      static_cast<int>(std::ceil(field.MaxDistance() / res) * std::ceil(field.MaxDistance() / res));
  std::vector<float> table(static_cast<std::size_t>(max_sq) + 2);
  for (std::size_t k = 0; k < table.size(); ++k) {
    const double d2 = static_cast<double>(k) * res * res;
    table[k] = static_cast<float>(std::exp(-0.5 * d2 / (lattice.sigma * lattice.sigma)));
  }
  auto score_of = [&](std::size_t index) {
    const float sq = field.SquaredDistanceCells(index);
    return sq <= static_cast<float>(max_sq) ? table[static_cast<std::size_t>(sq)] : 0.0F;
  };
  const std::size_t max_points = std::max<std::size_t>(1, lattice.max_points);
  const std::size_t stride =
      std::max<std::size_t>(1, (scan.points.size() + max_points - 1) / max_points);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < scan.points.size(); k += stride) {
    points.push_back(scan.points[k]);
  }
  *num_points = points.size();
  const int step = std::max(1, lattice.linear_step);
  const int linear_cells = static_cast<int>(std::floor(lattice.linear_window / res / step)) * step;
  const int angular_steps =
      static_cast<int>(std::floor(lattice.angular_window / lattice.angular_step));
  std::vector<Eigen::Array2i> cells(points.size());
  long evaluated = 0;
  for (int a = -angular_steps; a <= angular_steps; ++a) {
    const double theta = NormalizeAngle(centre.theta() + a * lattice.angular_step);
    const Pose2 rotated(centre.translation(), theta);
    for (std::size_t k = 0; k < points.size(); ++k) {
      cells[k] = limits.CellIndex(rotated * points[k]);
    }
    for (int dj = -linear_cells; dj <= linear_cells; dj += step) {
      for (int di = -linear_cells; di <= linear_cells; di += step) {
        float sum = 0.0F;
        for (const Eigen::Array2i& cell : cells) {
          const int i = cell.x() + di;
          const int j = cell.y() + dj;
          if (i >= 0 && j >= 0 && i < w && j < h) {
            sum += score_of(layout.Index(i, j));
          }
        }
        ++evaluated;
        visit(static_cast<double>(sum), a, di, dj, theta);
      }
    }
  }
  return evaluated;
}

}  // namespace

SearchResult CorrelativeSearch(const MatchingField& field, const ScanPoints& scan,
                               const Pose2& centre, const ScanMatcherOptions& options,
                               std::size_t max_points) {
  SearchLattice lattice;
  lattice.linear_window = options.search_linear_window;
  lattice.linear_step = options.search_linear_step;
  lattice.angular_window = options.search_angular_window;
  lattice.angular_step = options.search_angular_step;
  lattice.sigma = options.search_sigma;
  lattice.max_points = max_points;
  SearchResult best;
  best.T_odom_base = centre;
  const double res = field.Limits().Resolution();
  double best_score = -1.0;
  std::size_t n = 0;
  best.evaluated = ScoreLattice(
      field, scan, centre, lattice, &n, [&](double sum, int a, int di, int dj, double theta) {
        // Prefer the lattice pose nearest the centre among equal scores.
        const double score = sum - 1e-6 * (std::abs(a) + std::abs(di) + std::abs(dj));
        if (score > best_score) {
          best_score = score;
          best.score = sum / static_cast<double>(n);
          best.T_odom_base = Pose2(centre.translation() + Eigen::Vector2d(di, dj) * res, theta);
        }
      });
  return best;
}

std::vector<SearchResult> CorrelativeSearchTop(const MatchingField& field, const ScanPoints& scan,
                                               const Pose2& centre, const SearchLattice& lattice,
                                               int count, double separation_xy,
                                               double separation_theta) {
  struct Entry {
    double score;
    Pose2 pose;
  };
  const double res = field.Limits().Resolution();
  std::vector<Entry> entries;
  std::size_t n = 0;
  const long evaluated = ScoreLattice(
      field, scan, centre, lattice, &n, [&](double sum, int a, int di, int dj, double theta) {
        const double score = sum - 1e-6 * (std::abs(a) + std::abs(di) + std::abs(dj));
        entries.push_back(
            {score, Pose2(centre.translation() + Eigen::Vector2d(di, dj) * res, theta)});
      });
  std::vector<SearchResult> top;
  if (entries.empty() || count <= 0) {
    return top;
  }
  // Candidates in decreasing score; keep a pose unless a better kept one is near it.
  std::vector<std::size_t> order(entries.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    order[k] = k;
  }
  const std::size_t keep =
      std::min<std::size_t>(order.size(), 64 * static_cast<std::size_t>(count));
  std::partial_sort(
      order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(),
      [&](std::size_t a, std::size_t b) { return entries[a].score > entries[b].score; });
  for (std::size_t r = 0; r < keep && static_cast<int>(top.size()) < count; ++r) {
    const Entry& e = entries[order[r]];
    const bool near = std::any_of(top.begin(), top.end(), [&](const SearchResult& t) {
      return (t.T_odom_base.translation() - e.pose.translation()).norm() < separation_xy &&
             std::abs(NormalizeAngle(t.T_odom_base.theta() - e.pose.theta())) < separation_theta;
    });
    if (!near) {
      top.push_back({e.pose, e.score / static_cast<double>(n), evaluated});
    }
  }
  return top;
}

}  // namespace gridslam::scan_matching
