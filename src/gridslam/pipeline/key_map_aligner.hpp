// Aligning two key maps of the graph (docs/design.md §1.5, §1.6): the mapper's parts ask an Aligner
// for the pose of key map k in key map i's frame, and never look at features or grids
// themselves, so tests can script the answers (a ScriptedAligner on a synthetic graph).
// FeatureAligner is the real one: SURF matching + RANSAC + verification, refined on the
// distance field; with a prediction, a failed feature alignment falls back to refining the
// prediction (seeded by a correlative search when the uncertainty allows a large error).
#pragma once

#include <algorithm>
#include <list>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>

#include "gridslam/loop_closure/loop_closure_options.hpp"
#include "gridslam/matching/align.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"

namespace gridslam::pipeline {

/// A verified alignment.
struct Alignment {
  Pose2 T_i_k;
  /// Found by the correlative search around the prediction: never trusted alone (the arbiter
  /// treats it as outside the gate).
  bool from_search = false;
  /// Set for a ridge (a corridor, a straight road: the search's rivals all lie on one line): the
  /// direction, unit, in i's frame, along which T_i_k's translation is not measured.
  std::optional<Eigen::Vector2d> free_axis = std::nullopt;
  double free_sigma = 0.0;  ///< Standard deviation along free_axis (Match::free_sigma) [m].
  /// Found by the search's second, wide window (the first found nothing; prior_search.hpp).
  bool wide_search = false;
  /// Poorly constrained by the refinement along this direction (unit, in i's frame), placed by
  /// the search's distinct peak to within weak_sigma [m] (Match::weak_axis).
  std::optional<Eigen::Vector2d> weak_axis = std::nullopt;
  double weak_sigma = 0.0;

  /// The match of key maps i and k this alignment measures, with its free or weak axis.
  [[nodiscard]] loop_closure::Match ToMatch(int i, int k) const {
    return {i, k, T_i_k, free_axis, free_sigma, wide_search, weak_axis, weak_sigma};
  }
};

class Aligner {
 public:
  virtual ~Aligner() = default;
  /// The pose of key map k in i's frame, or nullopt when the two do not align (verified).
  /// `prior`: the predicted T_i_k, or null; `uncertainty_distance` between the two [m].
  virtual std::optional<Alignment> Align(int i, int k, const Pose2* prior,
                                         double uncertainty_distance) = 0;
};

/// What FeatureAligner counted.
struct AlignerCounters {
  long verified = 0;        ///< Alignments accepted by matching + verification.
  long prior_refined = 0;   ///< Found by refinement from the prediction.
  long prior_searches = 0;  ///< Correlative searches around the prediction.
  /// ... of them second, wide searches (the first found nothing), and the alignments they found
  /// (refined and verified).
  long prior_wide_searches = 0;
  long prior_wide_found = 0;
  long prior_ridges = 0;  ///< ... of them accepted as ridges (refined and verified).
  /// ... of them poorly constrained in the refinement, placed along the weak direction by the
  /// search's distinct peak.
  long prior_weak_by_search = 0;
  long geometry_recomputed = 0;  ///< Key-map geometries recomputed (not in the cache).
  /// Refinements that failed for want of points and were run again on a window of returns,
  /// and how many of those succeeded.
  long window_refinements = 0;
  long window_refined = 0;
};

/// The geometry (distance field, obstacle points) of the key maps used most recently, at most
/// `capacity` of them; the others are recomputed from their cells when an alignment needs them
/// (description::ComputeGeometry: the same values). Geometries are shared, so one evicted while
/// an alignment uses it stays alive until the alignment ends.
class GeometryCache {
 public:
  using Geometry = std::shared_ptr<const description::KeyMapGeometry>;
  explicit GeometryCache(int capacity) : capacity_(std::max(1, capacity)) {}
  /// The geometry of key map `id`, recomputed from `cells` if not cached.
  Geometry Get(int id, const description::KeyMapCells& cells);
  /// Stores the geometry of key map `id` (just described).
  void Put(int id, Geometry geometry);
  [[nodiscard]] long misses() const { return misses_; }
  /// Drops every stored geometry (later ones are recomputed, as for any miss).
  void Clear();
  [[nodiscard]] std::size_t size() const { return entries_.size(); }

 private:
  void Touch(std::list<std::pair<int, Geometry>>::iterator it);
  int capacity_;
  std::list<std::pair<int, Geometry>> entries_;  ///< Most recently used first.
  std::unordered_map<int, std::list<std::pair<int, Geometry>>::iterator> index_;
  long misses_ = 0;
};

/// The returns of key map k's scans and of its robot's preceding key maps, in k's frame (placed by
/// the front end's poses), newest first, while the path from them to k is at most `max_travel`
/// [m] and until `max_points` returns are collected (the last key map is taken whole).
std::vector<Eigen::Vector2d> RefinementWindow(const KeyMapGraph& graph, int k, double max_travel,
                                              int max_points);

class FeatureAligner : public Aligner {
 public:
  /// `graph` is borrowed (its key maps' descriptions are aligned).
  /// `cache_size`: key-map geometries kept (GeometryCache).
  FeatureAligner(const KeyMapGraph& graph, const matching::AlignOptions& matching,
                 const loop_closure::LoopClosureOptions& loop_closure, int cache_size = 256);
  std::optional<Alignment> Align(int i, int k, const Pose2* prior,
                                 double uncertainty_distance) override;
  /// The geometry of key map `id` as its description computed it (saves recomputing it for the
  /// alignments of a new key map).
  void Remember(int id, description::KeyMapGeometry geometry);
  /// Frees the cached geometries (the end of a run: no alignment follows, or it recomputes).
  void ReleaseCache() { cache_.Clear(); }
  [[nodiscard]] const AlignerCounters& counters() const { return counters_; }

 private:
  std::optional<Alignment> RefineFromPrior(int i, int k, const Pose2& T_i_k,
                                           const description::KeyMapGeometry& geometry_a,
                                           const description::KeyMapGeometry& geometry_b,
                                           double uncertainty_distance);
  [[nodiscard]] static std::span<const Eigen::Vector2d> RefinementPoints(
      const KeyMapNode& b, const description::KeyMapGeometry& geometry_b, int min_points);
  /// Refines T_a_b from `start` on RefinementPoints of k; when that fails for want of usable
  /// points, again on the returns of k and of its robot's preceding key maps (RefinementWindow).
  loop_closure::RefinementResult Refine(int k, const description::KeyMapGeometry& geometry_b,
                                        const Grid2D<float>& distance_a, const Pose2& start,
                                        const loop_closure::RefinementOptions& refinement);

  const KeyMapGraph& graph_;
  matching::AlignOptions matching_;
  loop_closure::LoopClosureOptions options_;
  AlignerCounters counters_;
  GeometryCache cache_;
};

}  // namespace gridslam::pipeline
