#include "gridslam/pose_graph/spanning_tree.hpp"

#include <algorithm>
#include <deque>

#include "gridslam/common/check.hpp"
#include "gridslam/pose_graph/graph_utils.hpp"

namespace gridslam::pose_graph {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

int OtherEnd(const PoseGraph& graph, int edge, int vertex) {
  return graph.FromIndex(edge) == vertex ? graph.ToIndex(edge) : graph.FromIndex(edge);
}

// Breadth-first attachment of every vertex not yet in the tree, from the vertices that are.
void CompleteBreadthFirst(const PoseGraph& graph, std::vector<int>& parent,
                          std::vector<bool>& in_tree) {
  const auto& incidence = graph.Incidence();
  std::deque<int> queue;
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    if (in_tree[U(v)]) {
      queue.push_back(v);
    }
  }
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    for (const int e : incidence[U(v)]) {
      const int w = OtherEnd(graph, e, v);
      if (!in_tree[U(w)]) {
        in_tree[U(w)] = true;
        parent[U(w)] = v;
        queue.push_back(w);
      }
    }
  }
}

}  // namespace

std::vector<int> BuildSpanningTree(const PoseGraph& graph, const std::vector<bool>& fixed,
                                   const std::string& kind) {
  const int n = static_cast<int>(graph.num_vertices());
  GRIDSLAM_CHECK(fixed.size() == U(n)) << "fixed flags must cover every vertex";
  std::vector<int> parent(U(n), -1);
  std::vector<bool> in_tree(fixed);
  if (kind == "chain") {
    const std::vector<int> parent_edge = ChainingTree(graph, fixed);
    for (int v = 0; v < n; ++v) {
      const int e = parent_edge[U(v)];
      GRIDSLAM_CHECK(e >= 0 || fixed[U(v)]) << "component without a fixed vertex";
      parent[U(v)] = e < 0 ? -1 : OtherEnd(graph, e, v);
    }
    return parent;
  }
  if (kind == "toro") {
    const auto& incidence = graph.Incidence();
    std::vector<int> order(U(n));
    for (int v = 0; v < n; ++v) {
      order[U(v)] = v;
    }
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return graph.vertex(a).id < graph.vertex(b).id; });
    for (const int v : order) {
      if (in_tree[U(v)]) {
        continue;
      }
      int best = -1;
      for (const int e : incidence[U(v)]) {
        const int w = OtherEnd(graph, e, v);
        if (in_tree[U(w)] && graph.vertex(w).id < graph.vertex(v).id &&
            (best < 0 || graph.vertex(w).id < graph.vertex(best).id)) {
          best = w;
        }
      }
      if (best >= 0) {
        parent[U(v)] = best;
        in_tree[U(v)] = true;
      }
    }
  } else {
    GRIDSLAM_CHECK(kind == "bfs") << "unknown spanning tree kind '" << kind << "'";
  }
  CompleteBreadthFirst(graph, parent, in_tree);
  GRIDSLAM_CHECK(std::all_of(in_tree.begin(), in_tree.end(), [](bool b) { return b; }))
      << "component without a fixed vertex";
  return parent;
}

}  // namespace gridslam::pose_graph
