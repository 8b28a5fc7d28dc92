// A cheap stand-in for covariance propagation in the loop-closure gates (docs/design.md §1.6):
// every pose-graph edge gets a weight in "metres of uncertainty" (a sequential edge its length, a
// loop edge a small constant), and the uncertainty distance between two key maps is the shortest
// weighted path between them (Dijkstra). Two key maps far apart along the chain but joined by an
// earlier closure are thus close, as their relative covariance is small.
#pragma once

#include <limits>
#include <vector>

namespace gridslam::loop_closure {

class UncertaintyGraph {
 public:
  static constexpr double kUnreachable = std::numeric_limits<double>::infinity();

  /// Adds a node; returns its index (0, 1, ...).
  int AddNode();
  /// Adds an undirected edge of `weight` >= 0 between existing nodes.
  void AddEdge(int a, int b, double weight);
  /// Shortest weighted path length from `source` to every node (kUnreachable if none).
  [[nodiscard]] std::vector<double> DistancesFrom(int source) const;
  /// The same, but only as far as `targets` need: the search stops once every target has its
  /// distance. Targets, and the nodes nearer than the farthest of them, hold exactly what
  /// DistancesFrom(source) gives; the others hold NaN (not computed). The cost grows with the
  /// part of the graph within the targets' distance, not with the whole graph.
  [[nodiscard]] std::vector<double> DistancesFrom(int source,
                                                  const std::vector<int>& targets) const;
  [[nodiscard]] int size() const { return static_cast<int>(adjacency_.size()); }

 private:
  struct Arc {
    int to;
    double weight;
  };
  std::vector<std::vector<Arc>> adjacency_;
};

}  // namespace gridslam::loop_closure
