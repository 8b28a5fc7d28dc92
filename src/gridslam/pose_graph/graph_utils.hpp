// Structure of a pose graph that every optimizer needs (docs/design.md §1.7, §1.9): connected
// components, one anchor per component (a graph file without FIX has a free gauge; g2o and Ceres
// fix the first vertex), and the odometry-chained initial guess used for edges-only files such as
// manhattan.g2o and for the benchmark protocol: each vertex is placed by composing edge
// measurements along a spanning tree that prefers small id gaps, which is the odometry chain
// (i-1 -> i) whenever the ids are consecutive along the trajectory.
#pragma once

#include <vector>

#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

struct Components {
  std::vector<int> component;  ///< Per vertex index, its component number (0..count-1).
  int count = 0;               ///< Number of connected components (isolated vertices included).
};

/// Connected components of the graph (edges taken as undirected). Components are numbered in
/// the order of their lowest vertex index.
Components ConnectedComponents(const PoseGraph& graph);

/// Per vertex index: true if the vertex is fixed in the graph, or if it is the lowest-id vertex of
/// a component that has no fixed vertex (the component's anchor).
std::vector<bool> EffectiveFixed(const PoseGraph& graph);

/// A spanning forest for chaining: per vertex index, the index of the edge to its parent, or -1
/// for roots. Roots are the vertices flagged in `fixed` (size num_vertices), plus the lowest-id
/// vertex of every component without one. Each component is grown by Prim's algorithm with the
/// id gap |id_i - id_j| as the edge weight (ties: lower edge index), so an odometry chain is
/// followed whenever it exists.
std::vector<int> ChainingTree(const PoseGraph& graph, const std::vector<bool>& fixed);

/// Sets every vertex that is not a root of ChainingTree(graph, EffectiveFixed(graph)) to its
/// parent's pose composed with the parent edge's measurement (or its inverse, for an edge that
/// points to the parent). Roots keep their poses.
void InitializeByChaining(PoseGraph& graph);

}  // namespace gridslam::pose_graph
