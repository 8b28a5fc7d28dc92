// Spanning forests of a pose graph for the tree parameterization of SGD (docs/method.md §4.2
// item 1; Olson et al. 2006 use the odometry chain, TORO's buildSimpleTree the smallest-id lower
// neighbour, TORO's buildMST a breadth-first tree). Every tree is rooted at fixed vertices.
#pragma once

#include <string>
#include <vector>

#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::pose_graph {

/// Per vertex index: its parent vertex index, or -1 for a root. Roots are exactly the vertices
/// with `fixed` set (size num_vertices; every component must contain one, checked).
/// `kind`: "bfs" (multi-source breadth-first from the roots: minimal depth), "chain"
/// (ChainingTree: smallest id gaps, the odometry chain) or "toro" (parent = the neighbour with the
/// smallest id below the vertex's own, where that neighbour is already in the tree when the
/// vertices are visited in id order; others fall back to breadth-first attachment).
std::vector<int> BuildSpanningTree(const PoseGraph& graph, const std::vector<bool>& fixed,
                                   const std::string& kind);

}  // namespace gridslam::pose_graph
