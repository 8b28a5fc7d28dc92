#include "gridslam/loop_closure/uncertainty_graph.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace gridslam::loop_closure {
namespace {

TEST(UncertaintyGraph, ShortestPathsThroughLoopEdges) {
  UncertaintyGraph g;
  for (int k = 0; k < 5; ++k) {
    g.AddNode();
  }
  g.AddEdge(0, 1, 1.0);
  g.AddEdge(1, 2, 1.0);
  g.AddEdge(2, 3, 1.0);
  g.AddEdge(0, 3, 0.5);  // a loop edge: 3 is close to 0
  const std::vector<double> d = g.DistancesFrom(0);
  EXPECT_DOUBLE_EQ(d[1], 1.0);
  EXPECT_DOUBLE_EQ(d[2], 1.5);
  EXPECT_DOUBLE_EQ(d[3], 0.5);
  EXPECT_EQ(d[4], UncertaintyGraph::kUnreachable);
}

// The search that stops at its targets gives them, and every node it settled, exactly the full
// search's distances; nodes it did not reach are NaN; unreachable targets make it search all.
TEST(UncertaintyGraph, TargetedSearchMatchesTheFullSearch) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 50; ++trial) {
    UncertaintyGraph g;
    const int n = 200;
    for (int k = 0; k < n; ++k) {
      g.AddNode();
    }
    std::uniform_real_distribution<double> weight(0.0, 2.0);
    for (int k = 1; k < n - 10; ++k) {
      g.AddEdge(k - 1, k, weight(rng));  // a chain; the last ten nodes stay apart
    }
    std::uniform_int_distribution<int> node(0, n - 11);
    for (int e = 0; e < 60; ++e) {
      g.AddEdge(node(rng), node(rng), 0.5);
    }
    const int source = node(rng);
    std::vector<int> targets;
    for (int t = 0; t < 5; ++t) {
      targets.push_back(node(rng));
    }
    if (trial % 10 == 0) {
      targets.push_back(n - 1);  // unreachable
    }
    const std::vector<double> full = g.DistancesFrom(source);
    const std::vector<double> part = g.DistancesFrom(source, targets);
    for (const int t : targets) {
      EXPECT_EQ(part[static_cast<std::size_t>(t)], full[static_cast<std::size_t>(t)]);
    }
    for (int v = 0; v < n; ++v) {
      const double p = part[static_cast<std::size_t>(v)];
      EXPECT_TRUE(std::isnan(p) || p == full[static_cast<std::size_t>(v)]) << v;
    }
  }
}

}  // namespace
}  // namespace gridslam::loop_closure
