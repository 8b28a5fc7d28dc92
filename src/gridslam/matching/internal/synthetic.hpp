// Synthetic inputs for the matching tests and benchmark (header-only, not part of the API):
// feature sets with known correspondences under a known T_a_b, and key-map grids cut from a world
// of wall segments, with ray-cast visibility so that cells hidden behind walls stay unknown.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/matching/feature_set.hpp"
#include "gridslam/matching/grid_verification.hpp"

namespace gridslam::matching::internal {

struct SyntheticPair {
  FeatureSet a;
  FeatureSet b;
  std::vector<Match> truth;  ///< The true correspondences (index_a, index_b).
};

/// `n_true` features seen by both maps (p_a = T_a_b * p_b + noise) among n_a and n_b features
/// spread over a square of side `extent` [m]; the rest are unrelated. Float descriptors of
/// length `dim`, near-copies for the true pairs; signs, scales and angles filled consistently.
inline SyntheticPair MakeFeaturePair(const Pose2& T_a_b, int n_a, int n_b, int n_true,
                                     double position_noise, unsigned seed, int dim = 64,
                                     double extent = 10.0, double descriptor_noise = 0.05) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-0.5 * extent, 0.5 * extent);
  std::uniform_real_distribution<double> scale(0.2, 1.0);
  std::uniform_real_distribution<double> angle(-3.14159, 3.14159);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto random_descriptor = [&](cv::Mat row) {
    double norm = 0.0;
    for (int c = 0; c < dim; ++c) {
      row.at<float>(0, c) = static_cast<float>(gauss(rng));
      norm += row.at<float>(0, c) * row.at<float>(0, c);
    }
    row /= std::sqrt(norm);
  };
  const auto perturb = [&](const cv::Mat& base, cv::Mat row) {
    double norm = 0.0;
    for (int c = 0; c < dim; ++c) {
      row.at<float>(0, c) =
          base.at<float>(0, c) + static_cast<float>(descriptor_noise * gauss(rng));
      norm += row.at<float>(0, c) * row.at<float>(0, c);
    }
    row /= std::sqrt(norm);
  };
  // Random orders so that true pairs do not share indices.
  std::vector<int> order_a(static_cast<std::size_t>(n_a));
  std::vector<int> order_b(static_cast<std::size_t>(n_b));
  for (int i = 0; i < n_a; ++i) order_a[static_cast<std::size_t>(i)] = i;
  for (int i = 0; i < n_b; ++i) order_b[static_cast<std::size_t>(i)] = i;
  std::shuffle(order_a.begin(), order_a.end(), rng);
  std::shuffle(order_b.begin(), order_b.end(), rng);

  SyntheticPair pair;
  for (FeatureSet* set : {&pair.a, &pair.b}) {
    const int n = set == &pair.a ? n_a : n_b;
    set->points.resize(static_cast<std::size_t>(n));
    set->descriptors = cv::Mat(n, dim, CV_32F);
    set->laplacian_sign.resize(static_cast<std::size_t>(n));
    set->scales.resize(static_cast<std::size_t>(n));
    set->angles.resize(static_cast<std::size_t>(n));
  }
  cv::Mat base(1, dim, CV_32F);
  for (int k = 0; k < std::max(n_a, n_b); ++k) {
    const bool both = k < n_true;
    const int ia = k < n_a ? order_a[static_cast<std::size_t>(k)] : -1;
    const int ib = k < n_b ? order_b[static_cast<std::size_t>(k)] : -1;
    const Eigen::Vector2d p_b(pos(rng), pos(rng));
    const int sign = gauss(rng) > 0.0 ? 1 : -1;
    const double s = scale(rng);
    const double ang = angle(rng);
    random_descriptor(base);
    if (ib >= 0) {
      const auto u = static_cast<std::size_t>(ib);
      pair.b.points[u] = p_b;
      perturb(base, pair.b.descriptors.row(ib));
      pair.b.laplacian_sign[u] = sign;
      pair.b.scales[u] = s;
      pair.b.angles[u] = ang;
    }
    if (ia >= 0) {
      const auto u = static_cast<std::size_t>(ia);
      if (both) {
        pair.a.points[u] = T_a_b * p_b + position_noise * Eigen::Vector2d(gauss(rng), gauss(rng));
        perturb(base, pair.a.descriptors.row(ia));
        pair.a.laplacian_sign[u] = sign;
        pair.a.scales[u] = s;
        pair.a.angles[u] = NormalizeAngle(ang + T_a_b.theta() + 0.05 * gauss(rng));
        pair.truth.push_back({ia, ib, 0.0F});
      } else {
        pair.a.points[u] = Eigen::Vector2d(pos(rng), pos(rng));
        random_descriptor(pair.a.descriptors.row(ia));
        pair.a.laplacian_sign[u] = gauss(rng) > 0.0 ? 1 : -1;
        pair.a.scales[u] = scale(rng);
        pair.a.angles[u] = angle(rng);
      }
    }
  }
  return pair;
}

struct Segment {
  Eigen::Vector2d p;
  Eigen::Vector2d q;
};

inline double DistanceToSegment(const Eigen::Vector2d& x, const Segment& s) {
  const Eigen::Vector2d d = s.q - s.p;
  const double t = std::clamp((x - s.p).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.p + t * d - x).norm();
}

// Parameter u in [0, 1] along o->x where the segment crosses it, or > 1 if it does not.
inline double RayHit(const Eigen::Vector2d& o, const Eigen::Vector2d& x, const Segment& s) {
  const Eigen::Vector2d r = x - o;
  const Eigen::Vector2d e = s.q - s.p;
  const double den = r.x() * e.y() - r.y() * e.x();
  if (std::abs(den) < 1e-12) {
    return 2.0;
  }
  const Eigen::Vector2d w = s.p - o;
  const double u = (w.x() * e.y() - w.y() * e.x()) / den;
  const double v = (w.x() * r.y() - w.y() * r.x()) / den;
  return (u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0) ? u : 2.0;
}

/// A key map, its obstacle points and distance field, all in the key map's frame.
struct SyntheticKeyMap {
  OccupancyImage occupancy;
  Grid2D<float> distance;
  std::vector<Eigen::Vector2d> obstacles;
};

/// The key map of side `side` [m] centred at T_world_key, seeing the world's walls within
/// `radius` of its centre, with resolution `resolution` [m].
inline SyntheticKeyMap MakeKeyMap(const std::vector<Segment>& world, const Pose2& T_world_key,
                                  double side = 12.0, double radius = 6.0,
                                  double resolution = 0.05) {
  const int n = static_cast<int>(std::lround(side / resolution));
  const MapLimits limits(resolution, Eigen::Vector2d(-0.5 * side, -0.5 * side), n, n);
  SyntheticKeyMap map;
  map.occupancy = OccupancyImage(limits, kUnknownCell);
  const Eigen::Vector2d o = T_world_key.translation();
  cv::Mat obstacle_image(n, n, CV_8U, cv::Scalar(255));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d w = T_world_key * limits.CellCenter({i, j});
      const double range = (w - o).norm();
      if (range > radius) {
        continue;
      }
      double nearest = 1e9;
      double first_hit = 2.0;
      for (const Segment& s : world) {
        nearest = std::min(nearest, DistanceToSegment(w, s));
        first_hit = std::min(first_hit, RayHit(o, w, s));
      }
      const double hidden_by = (1.0 - first_hit) * range;  // distance before w where a wall is hit
      if (nearest <= 0.55 * resolution) {                  // a wall on a cell boundary marks both
        if (hidden_by <= 1.5 * resolution) {
          map.occupancy(i, j) = kOccupiedCell;
          obstacle_image.at<std::uint8_t>(j, i) = 0;
        }
      } else if (first_hit > 1.0) {
        map.occupancy(i, j) = kFreeCell;
      }
    }
  }
  cv::Mat dist;
  cv::distanceTransform(obstacle_image, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  map.distance = Grid2D<float>(limits, 0.0F);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      map.distance(i, j) = dist.at<float>(j, i) * static_cast<float>(resolution);
    }
  }
  MarkUnknownCells(map.occupancy, &map.distance);
  map.obstacles = OccupiedCellCenters(map.occupancy);
  return map;
}

/// A corridor along x (y in [-1, 1], x in [-14, 14]) with rooms on its north side every 4 m
/// (doors centred at x = -10, -6, ..., 10) and an irregular south side: locally periodic, so a
/// shift by 4 m along x is a look-alike that only the south side and the ends give away.
inline std::vector<Segment> CorridorWorld() {
  std::vector<Segment> w;
  const auto add = [&w](double x0, double y0, double x1, double y1) {
    w.push_back({Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1)});
  };
  add(-14, -1, -14, 4);  // west end
  add(14, -1, 14, 4);    // east end
  add(-14, 4, 14, 4);    // back wall of the rooms
  for (int k = -3; k <= 3; ++k) {
    add(4.0 * k, 1, 4.0 * k, 4);  // room partitions
  }
  for (int k = -3; k <= 2; ++k) {
    add(4.0 * k + 2.5, 1, 4.0 * k + 5.5, 1);  // north wall between the doors
  }
  add(-14, 1, -10.5, 1);
  add(13.5, 1, 14, 1);
  // South side: walls with openings at irregular places and alcoves of different depths.
  add(-14, -1, -9.0, -1);
  add(-9.0, -1, -9.0, -3.0);
  add(-7.5, -1, -7.5, -3.0);
  add(-9.0, -3.0, -7.5, -3.0);
  add(-7.5, -1, 1.0, -1);
  add(1.0, -1, 1.0, -2.0);
  add(1.0, -2.0, 3.5, -2.0);
  add(3.5, -2.0, 3.5, -1);
  add(3.5, -1, 5.0, -1);
  add(6.5, -1, 14, -1);
  add(5.0, -1, 5.0, -4.0);
  add(6.5, -1, 6.5, -4.0);
  add(5.0, -4.0, 6.5, -4.0);
  return w;
}

}  // namespace gridslam::matching::internal
