#include "gridslam/loop_closure/uncertainty_graph.hpp"

#include <functional>
#include <queue>
#include <utility>

#include "gridslam/common/check.hpp"

namespace gridslam::loop_closure {

int UncertaintyGraph::AddNode() {
  adjacency_.emplace_back();
  return size() - 1;
}

void UncertaintyGraph::AddEdge(int a, int b, double weight) {
  GRIDSLAM_CHECK(a >= 0 && b >= 0 && a < size() && b < size()) << a << " " << b;
  GRIDSLAM_CHECK(weight >= 0.0) << weight;
  adjacency_[static_cast<std::size_t>(a)].push_back({b, weight});
  adjacency_[static_cast<std::size_t>(b)].push_back({a, weight});
}

std::vector<double> UncertaintyGraph::DistancesFrom(int source) const {
  std::vector<double> distance(adjacency_.size(), kUnreachable);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  distance[static_cast<std::size_t>(source)] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[static_cast<std::size_t>(v)]) {
      continue;
    }
    for (const Arc& arc : adjacency_[static_cast<std::size_t>(v)]) {
      const double nd = d + arc.weight;
      if (nd < distance[static_cast<std::size_t>(arc.to)]) {
        distance[static_cast<std::size_t>(arc.to)] = nd;
        queue.emplace(nd, arc.to);
      }
    }
  }
  return distance;
}

}  // namespace gridslam::loop_closure
