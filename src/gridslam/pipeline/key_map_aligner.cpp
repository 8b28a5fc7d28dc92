#include "gridslam/pipeline/key_map_aligner.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "gridslam/common/logging.hpp"
#include "gridslam/loop_closure/grid_refinement.hpp"

namespace gridslam::pipeline {

GeometryCache::Geometry GeometryCache::Get(int id, const description::KeyMapCells& cells) {
  if (const auto it = index_.find(id); it != index_.end()) {
    Touch(it->second);
    return it->second->second;
  }
  ++misses_;
  Geometry geometry =
      std::make_shared<const description::KeyMapGeometry>(description::ComputeGeometry(cells));
  Put(id, geometry);
  return geometry;
}

void GeometryCache::Clear() {
  entries_.clear();
  index_.clear();
}

void GeometryCache::Put(int id, Geometry geometry) {
  if (const auto it = index_.find(id); it != index_.end()) {
    it->second->second = std::move(geometry);
    Touch(it->second);
    return;
  }
  entries_.emplace_front(id, std::move(geometry));
  index_[id] = entries_.begin();
  while (static_cast<int>(entries_.size()) > capacity_) {
    index_.erase(entries_.back().first);
    entries_.pop_back();
  }
}

void GeometryCache::Touch(std::list<std::pair<int, Geometry>>::iterator it) {
  entries_.splice(entries_.begin(), entries_, it);
}

FeatureAligner::FeatureAligner(const KeyMapGraph& graph, const matching::AlignOptions& matching,
                               const loop_closure::LoopClosureOptions& loop_closure, int cache_size)
    : graph_(graph), matching_(matching), options_(loop_closure), cache_(cache_size) {}

void FeatureAligner::Remember(int id, description::KeyMapGeometry geometry) {
  cache_.Put(id, std::make_shared<const description::KeyMapGeometry>(std::move(geometry)));
}

std::span<const Eigen::Vector2d> FeatureAligner::RefinementPoints(
    const KeyMapNode& b, const description::KeyMapGeometry& geometry_b, int min_points) {
  return b.scan_points.size() >= 2 * static_cast<std::size_t>(min_points)
             ? std::span<const Eigen::Vector2d>(b.scan_points)
             : std::span<const Eigen::Vector2d>(geometry_b.obstacle_points);
}

std::vector<Eigen::Vector2d> RefinementWindow(const KeyMapGraph& graph, int k, double max_travel,
                                              int max_points) {
  const KeyMapNode& b = graph.node(k);
  std::vector<Eigen::Vector2d> points = b.scan_points;
  const Pose2 T_key_odom = b.T_odom_key.Inverse();
  for (int id = b.previous; id >= 0 && static_cast<int>(points.size()) < max_points;) {
    const KeyMapNode& before = graph.node(id);
    if (b.travel - before.travel > max_travel) {
      break;
    }
    const PointTransform to_b(T_key_odom * before.T_odom_key);
    for (const Eigen::Vector2d& p : before.scan_points) {
      points.push_back(to_b(p));
    }
    id = before.previous;
  }
  return points;
}

loop_closure::RefinementResult FeatureAligner::Refine(
    int k, const description::KeyMapGeometry& geometry_b, const Grid2D<float>& distance_a,
    const Pose2& start, const loop_closure::RefinementOptions& refinement) {
  const KeyMapNode& b = graph_.node(k);
  const std::span<const Eigen::Vector2d> points =
      RefinementPoints(b, geometry_b, refinement.min_points);
  loop_closure::RefinementResult refined =
      loop_closure::RefineOnDistanceField(points, distance_a, start, refinement);
  if (refined.ok || refined.points >= refinement.min_points || refinement.points != "scans" ||
      refinement.window_travel <= 0.0 || b.previous < 0) {
    return refined;
  }
  const std::vector<Eigen::Vector2d> window =
      RefinementWindow(graph_, k, refinement.window_travel, refinement.max_points);
  if (window.size() <= b.scan_points.size()) {
    return refined;
  }
  ++counters_.window_refinements;
  loop_closure::RefinementResult again =
      loop_closure::RefineOnDistanceField(window, distance_a, start, refinement);
  counters_.window_refined += again.ok ? 1 : 0;
  GRIDSLAM_LOG_DEBUG("refinement of {}: {} usable of {} points, window of {}: {}", k,
                     refined.points, points.size(), window.size(), again.ok ? "ok" : "failed");
  return again;
}

namespace {

matching::VerificationInput Verification(const description::KeyMapGeometry& a,
                                         const description::KeyMapGeometry& b) {
  matching::VerificationInput input;
  input.points_b = b.obstacle_points;
  input.distance_a = &a.distance;
  input.points_a = a.obstacle_points;
  input.distance_b = &b.distance;
  return input;
}

}  // namespace

std::optional<Alignment> FeatureAligner::Align(int i, int k, const Pose2* prior,
                                               double uncertainty_distance) {
  const KeyMapNode& a = graph_.node(i);
  const KeyMapNode& b = graph_.node(k);
  // Matching and RANSAC first; the geometries (distance fields, obstacle points) only when the
  // verification or the refinement reads them: as matching::Align with a VerificationInput.
  matching::AlignResult result = matching::Align(a.features, b.features, matching_, nullptr);
  const bool refine_prior = prior != nullptr && options_.prior_refinement;
  if (!result.accepted && !refine_prior) {
    return std::nullopt;
  }
  const long cached_misses = cache_.misses();
  const GeometryCache::Geometry geometry_a = cache_.Get(i, a.cells);
  const GeometryCache::Geometry geometry_b = cache_.Get(k, b.cells);
  counters_.geometry_recomputed += cache_.misses() - cached_misses;
  if (result.accepted && matching_.verification.enabled) {
    const matching::VerificationResult verified = matching::VerifyAlignment(
        result.T_a_b, Verification(*geometry_a, *geometry_b), matching_.verification);
    result.accepted = verified.enough_overlap && verified.accepted;
  }
  if (!result.accepted) {
    return refine_prior
               ? RefineFromPrior(i, k, *prior, *geometry_a, *geometry_b, uncertainty_distance)
               : std::nullopt;
  }
  ++counters_.verified;
  Pose2 T_a_b = result.T_a_b;
  if (options_.refinement.enabled) {
    const loop_closure::RefinementResult refined =
        Refine(k, *geometry_b, geometry_a->distance, T_a_b, options_.refinement);
    if (refined.ok) {
      T_a_b = refined.T_a_b;
    }
  }
  return Alignment{T_a_b, false};
}

std::optional<Alignment> FeatureAligner::RefineFromPrior(
    int i, int k, const Pose2& T_i_k, const description::KeyMapGeometry& geometry_a,
    const description::KeyMapGeometry& geometry_b, double uncertainty_distance) {
  loop_closure::RefinementOptions refinement = options_.refinement;
  refinement.max_distance = std::max(refinement.max_distance, 0.5);
  // After a long loop the prediction may be off by more than the refinement converges from.
  const loop_closure::PriorSearchOptions& search = options_.prior_search;
  const double window = search.WindowXy(uncertainty_distance);
  const double window_theta = search.WindowTheta(uncertainty_distance);
  Pose2 start = T_i_k;
  bool searched = false;
  bool wide = false;
  std::optional<Eigen::Vector2d> free_axis;
  double free_sigma = 0.0;
  if (search.enabled && window > search.min_window_xy) {
    const auto run = [&](double half_window) {
      ++counters_.prior_searches;
      const loop_closure::PriorSearchResult found =
          loop_closure::SearchAroundPrior(geometry_b.obstacle_points, geometry_a.distance, T_i_k,
                                          half_window, window_theta, search);
      if (found.score < search.min_score) {
        GRIDSLAM_LOG_DEBUG(
            "prior search {}-{}: window {:.2f} m {:.2f} rad, no pose reaches min_score {:.2f}, "
            "{} of {} poses scored, refused",
            i, k, half_window, window_theta, search.min_score, found.scored, found.poses);
      } else {
        GRIDSLAM_LOG_DEBUG(
            "prior search {}-{}: window {:.2f} m {:.2f} rad, score {:.3f}, rival {:.3f}, {} of {} "
            "poses scored, {}",
            i, k, half_window, window_theta, found.score, found.rival, found.scored, found.poses,
            found.ok ? "ok" : "refused");
      }
      return found;
    };
    loop_closure::PriorSearchResult found = run(window);
    // Nothing in the window of the usual drift: the drift the arbiter allows, if that is more
    // than a search step wider (a look-alike may win there: its closures need independent
    // support).
    const double wide_window = search.WideWindowXy(uncertainty_distance);
    if (!found.ok && wide_window > window + search.linear_step) {
      found = run(wide_window);
      wide = found.ok;
      ++counters_.prior_wide_searches;
    }
    if (!found.ok) {
      return std::nullopt;
    }
    start = found.T_a_b;
    searched = true;
    if (found.ridge) {
      free_axis = found.ridge_axis;
      free_sigma = (wide ? wide_window : window) / std::sqrt(3.0);
    }
  }
  const loop_closure::RefinementResult refined =
      Refine(k, geometry_b, geometry_a.distance, start, refinement);
  if (!refined.ok || refined.inlier_fraction < options_.prior_min_inliers) {
    GRIDSLAM_LOG_DEBUG("prior refinement {}-{}: refused, ok {}, inliers {:.2f}", i, k, refined.ok,
                       refined.inlier_fraction);
    return std::nullopt;
  }
  // Degenerate geometry (a corridor) constrains some direction poorly in the refinement, which
  // sees only the distance field's local slope. A ridge (the search found the direction flat)
  // needs the direction across it constrained. When the search found one distinct peak, the
  // search measured the weak direction, by scoring the whole window (a door, a bay, the end of
  // the corridor): the position along it is the search's, the rest the refinement's. Without a
  // search nothing measured it: refused.
  const Eigen::Matrix2d hessian_xy = refined.hessian.topLeftCorner<2, 2>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(hessian_xy);
  double weakest = eig.eigenvalues()(0);
  if (free_axis.has_value()) {
    const Eigen::Vector2d across(-free_axis->y(), free_axis->x());
    weakest = across.dot(hessian_xy * across);
  }
  Pose2 T_a_b = refined.T_a_b;
  std::optional<Eigen::Vector2d> weak_axis;
  if (weakest < options_.prior_min_constraint * eig.eigenvalues()(1)) {
    if (!searched || free_axis.has_value()) {
      GRIDSLAM_LOG_DEBUG("prior refinement {}-{}: refused, poorly constrained{}", i, k,
                         free_axis.has_value() ? " across the ridge" : "");
      return std::nullopt;
    }
    // The refinement may slide along the weak direction: keep it within the search's step of
    // the search's peak.
    const Eigen::Vector2d weak = eig.eigenvectors().col(0);
    const Eigen::Vector2d t = refined.T_a_b.translation();
    const double slid = weak.dot(t - start.translation());
    const double kept = std::clamp(slid, -search.linear_step, search.linear_step);
    const Eigen::Vector2d moved = weak * (kept - slid);
    T_a_b = Pose2(t.x() + moved.x(), t.y() + moved.y(), refined.T_a_b.theta());
    weak_axis = weak;
    GRIDSLAM_LOG_DEBUG(
        "prior refinement {}-{}: poorly constrained along ({:.2f}, {:.2f}), slid {:.3f} m from "
        "the search's peak, kept {:.3f} m",
        i, k, weak.x(), weak.y(), slid, kept);
  }
  const matching::VerificationResult verified = matching::VerifyAlignment(
      T_a_b, Verification(geometry_a, geometry_b), matching_.verification);
  if (!verified.accepted) {
    GRIDSLAM_LOG_DEBUG(
        "prior refinement {}-{}: not verified, overlap {} ({}), agreement {:.2f}, contradiction "
        "{:.2f}",
        i, k, verified.overlap, verified.enough_overlap, verified.agreement,
        verified.contradiction);
    return std::nullopt;
  }
  ++counters_.prior_refined;
  counters_.prior_ridges += free_axis.has_value() ? 1 : 0;
  counters_.prior_wide_found += wide ? 1 : 0;
  counters_.prior_weak_by_search += weak_axis.has_value() ? 1 : 0;
  // Along the weak direction the translation is known to within the search's step (uniform over
  // +-linear_step, as kept above).
  const double weak_sigma = weak_axis.has_value() ? search.linear_step / std::sqrt(3.0) : 0.0;
  return Alignment{T_a_b, searched, free_axis, free_sigma, wide, weak_axis, weak_sigma};
}

}  // namespace gridslam::pipeline
