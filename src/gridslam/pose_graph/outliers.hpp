// Wrong loop closures for the outlier benchmark (robust_optimization.md), after Sünderhauf's
// Vertigo (Sünderhauf & Protzel 2012): edges with wrong measurements are added to a graph, and the
// result of optimizing it is compared with the clean graph's optimum by the mean position error.
//  - random: random vertex pairs, random relative poses;
//  - local: pairs at most `local_window` ids apart (never consecutive), random small poses;
//  - group: groups of `group_size` edges (i + k, j + k) sharing one random relative pose, so the
//    edges of a group agree with each other (harder: they support each other against the rest).
// Every outlier gets the information of the graph's first odometry edge (consecutive ids) and the
// role kLoopClosure. Deterministic for a seed.
#pragma once

#include <string>
#include <vector>

#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

enum class OutlierKind { kRandom, kLocal, kGroup };

struct OutlierOptions {
  int count = 10;  ///< Edges to add (group: rounded up to whole groups, then cut at count).
  OutlierKind kind = OutlierKind::kRandom;
  unsigned seed = 1;
  double max_translation = 10.0;   ///< random/group: |dx|, |dy| uniform up to this [m].
  double local_translation = 2.0;  ///< local: |dx|, |dy| uniform up to this [m].
  int local_window = 20;           ///< local: id gap 2..local_window.
  int group_size = 10;             ///< group: edges per group.
};

/// Parses "random", "local" or "group"; false for anything else.
bool ParseOutlierKind(const std::string& name, OutlierKind* kind);

/// Adds `options.count` wrong edges to `graph` (needs >= 3 vertices and one edge, checked) and
/// returns their edge indices.
std::vector<int> AddOutliers(PoseGraph& graph, const OutlierOptions& options);

struct PoseErrors {
  double mean_translation = 0.0;  ///< Mean over vertices of |t - t_ref| [m].
  double max_translation = 0.0;   ///< [m].
  double mean_rotation = 0.0;     ///< Mean |wrapped theta - theta_ref| [rad].
};

/// Errors of `graph`'s poses against `reference` vertex by vertex (same vertex ids in the same
/// order, checked). No alignment: both are anchored at the same vertex (EffectiveFixed).
PoseErrors ComparePoses(const PoseGraph& graph, const PoseGraph& reference);

}  // namespace gridslam::pose_graph
