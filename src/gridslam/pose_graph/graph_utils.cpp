#include "gridslam/pose_graph/graph_utils.hpp"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <queue>
#include <tuple>

#include "gridslam/common/check.hpp"

namespace gridslam::pose_graph {

namespace {

std::size_t U(int i) { return static_cast<std::size_t>(i); }

int OtherEnd(const PoseGraph& graph, int edge, int vertex) {
  return graph.FromIndex(edge) == vertex ? graph.ToIndex(edge) : graph.FromIndex(edge);
}

}  // namespace

Components ConnectedComponents(const PoseGraph& graph) {
  const int n = static_cast<int>(graph.num_vertices());
  const auto& incidence = graph.Incidence();
  Components result;
  result.component.assign(U(n), -1);
  std::vector<int> stack;
  for (int start = 0; start < n; ++start) {
    if (result.component[U(start)] >= 0) {
      continue;
    }
    const int c = result.count++;
    result.component[U(start)] = c;
    stack.push_back(start);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (const int e : incidence[U(v)]) {
        const int w = OtherEnd(graph, e, v);
        if (result.component[U(w)] < 0) {
          result.component[U(w)] = c;
          stack.push_back(w);
        }
      }
    }
  }
  return result;
}

std::vector<bool> EffectiveFixed(const PoseGraph& graph) {
  const Components components = ConnectedComponents(graph);
  std::vector<bool> fixed(graph.num_vertices(), false);
  std::vector<int> anchor(U(components.count), -1);
  std::vector<bool> has_fixed(U(components.count), false);
  for (int v = 0; v < static_cast<int>(graph.num_vertices()); ++v) {
    const int c = components.component[U(v)];
    if (graph.vertex(v).fixed) {
      fixed[U(v)] = true;
      has_fixed[U(c)] = true;
    }
    if (anchor[U(c)] < 0 || graph.vertex(v).id < graph.vertex(anchor[U(c)]).id) {
      anchor[U(c)] = v;
    }
  }
  for (int c = 0; c < components.count; ++c) {
    if (!has_fixed[U(c)]) {
      fixed[U(anchor[U(c)])] = true;
    }
  }
  return fixed;
}

std::vector<int> ChainingTree(const PoseGraph& graph, const std::vector<bool>& fixed) {
  const int n = static_cast<int>(graph.num_vertices());
  GRIDSLAM_CHECK(fixed.size() == U(n)) << "fixed flags must cover every vertex";
  const auto& incidence = graph.Incidence();
  std::vector<int> parent_edge(U(n), -1);
  std::vector<bool> reached(U(n), false);
  // (id gap, edge index, vertex to reach through it).
  using Item = std::tuple<long, int, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  auto reach = [&](int v) {
    reached[U(v)] = true;
    for (const int e : incidence[U(v)]) {
      const int w = OtherEnd(graph, e, v);
      if (!reached[U(w)]) {
        const long gap = std::labs(static_cast<long>(graph.vertex(w).id) - graph.vertex(v).id);
        queue.emplace(gap, e, w);
      }
    }
  };
  auto grow = [&]() {
    while (!queue.empty()) {
      const auto [gap, e, w] = queue.top();
      queue.pop();
      if (!reached[U(w)]) {
        parent_edge[U(w)] = e;
        reach(w);
      }
    }
  };
  // Fixed vertices first (all at once: a component with several of them is split between them).
  for (int v = 0; v < n; ++v) {
    if (fixed[U(v)]) {
      reach(v);
    }
  }
  grow();
  // Components without a fixed vertex: start from their lowest id.
  std::vector<int> order(U(n));
  for (int v = 0; v < n; ++v) {
    order[U(v)] = v;
  }
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return graph.vertex(a).id < graph.vertex(b).id; });
  for (const int v : order) {
    if (!reached[U(v)]) {
      reach(v);
      grow();
    }
  }
  return parent_edge;
}

void InitializeByChaining(PoseGraph& graph) {
  const std::vector<int> parent_edge = ChainingTree(graph, EffectiveFixed(graph));
  // Visit in tree order: a vertex is placed after its parent (BFS over children lists).
  const int n = static_cast<int>(graph.num_vertices());
  std::vector<std::vector<int>> children(U(n));
  std::vector<int> roots;
  for (int v = 0; v < n; ++v) {
    const int e = parent_edge[U(v)];
    if (e < 0) {
      roots.push_back(v);
    } else {
      children[U(OtherEnd(graph, e, v))].push_back(v);
    }
  }
  std::vector<int> stack = roots;
  while (!stack.empty()) {
    const int p = stack.back();
    stack.pop_back();
    for (const int v : children[U(p)]) {
      const int e = parent_edge[U(v)];
      const Pose2& z = graph.edge(e).T_i_j;
      const Pose2& T_map_p = graph.vertex(p).T_map_v;
      graph.SetPose(v, graph.FromIndex(e) == p ? T_map_p * z : T_map_p * z.Inverse());
      stack.push_back(v);
    }
  }
}

}  // namespace gridslam::pose_graph
