#include "gridslam/loop_closure/uncertainty_graph.hpp"

#include <functional>
#include <limits>
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
  return DistancesFrom(source, {});
}

std::vector<double> UncertaintyGraph::DistancesFrom(int source,
                                                    const std::vector<int>& targets) const {
  std::vector<double> distance(adjacency_.size(), kUnreachable);
  // Without targets: every node. Else the targets still unsettled, counted down.
  std::vector<char> wanted(targets.empty() ? 0 : adjacency_.size(), 0);
  std::size_t missing = 0;
  for (const int t : targets) {
    GRIDSLAM_CHECK(t >= 0 && t < size()) << t;
    if (wanted[static_cast<std::size_t>(t)] == 0) {
      wanted[static_cast<std::size_t>(t)] = 1;
      ++missing;
    }
  }
  std::vector<char> settled(targets.empty() ? 0 : adjacency_.size(), 0);
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
    if (!targets.empty()) {
      if (settled[static_cast<std::size_t>(v)] == 0) {
        settled[static_cast<std::size_t>(v)] = 1;
        if (wanted[static_cast<std::size_t>(v)] != 0 && --missing == 0) {
          break;
        }
      }
    }
    for (const Arc& arc : adjacency_[static_cast<std::size_t>(v)]) {
      const double nd = d + arc.weight;
      if (nd < distance[static_cast<std::size_t>(arc.to)]) {
        distance[static_cast<std::size_t>(arc.to)] = nd;
        queue.emplace(nd, arc.to);
      }
    }
  }
  if (!targets.empty() && missing == 0) {
    // Stopped early: what was not settled is not known.
    for (std::size_t v = 0; v < distance.size(); ++v) {
      if (settled[v] == 0) {
        distance[v] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  return distance;
}

}  // namespace gridslam::loop_closure
