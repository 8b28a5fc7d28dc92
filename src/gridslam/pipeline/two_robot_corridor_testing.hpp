// Test fixture of the joining tests (component_joiner_test, join_verifier_test): two robots
// drive the same corridor, each mapping in its own frame, and an aligner that answers with the
// true relative pose of key maps near each other in truth, or a scripted one.
#pragma once

#include <map>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "gridslam/loop_closure/closure_arbiter.hpp"
#include "gridslam/pipeline/key_map_aligner.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"

namespace gridslam::pipeline::testing {

/// Answers with the true relative pose of key maps within `range` of each other (in truth), or a
/// scripted wrong answer; with `free_axis` set, every answer is a ridge along it.
class ScriptedAligner : public Aligner {
 public:
  ScriptedAligner(std::vector<Pose2> truth, double range)
      : truth_(std::move(truth)), range_(range) {}
  std::optional<Alignment> Align(int i, int k, const Pose2*, double) override {
    ++calls;
    if (const auto it = wrong.find({i, k}); it != wrong.end()) {
      return Alignment{it->second, false, free_axis, free_axis.has_value() ? 1.0 : 0.0};
    }
    const Pose2& a = truth_[static_cast<std::size_t>(i)];
    const Pose2& b = truth_[static_cast<std::size_t>(k)];
    if ((a.translation() - b.translation()).norm() > range_) {
      return std::nullopt;
    }
    return Alignment{Between(a, b), false, free_axis, free_axis.has_value() ? 1.0 : 0.0};
  }
  std::map<std::pair<int, int>, Pose2> wrong;
  std::optional<Eigen::Vector2d> free_axis;
  int calls = 0;

 private:
  std::vector<Pose2> truth_;
  double range_;
};

/// Adds `node` to `graph` with a sequential edge from its robot's previous key map (its odometry,
/// 2 cm / 0.005 rad), of uncertainty weight `travelled` [m].
inline void AppendKeyMap(KeyMapGraph* graph, KeyMapNode node, double travelled) {
  const int robot = node.robot;
  const int previous = graph->LastKeyMap(robot);
  const int id = graph->AddKeyMap(std::move(node));
  if (previous >= 0) {
    EdgeRecord edge;
    edge.from = previous;
    edge.to = id;
    edge.T_from_to = Between(graph->node(previous).T_odom_key, graph->node(id).T_odom_key);
    edge.information = Information(0.02, 0.005);
    graph->AddEdge(edge, travelled);
  }
}

struct Team {
  KeyMapGraph graph{2, {}};
  std::vector<Pose2> truth;
  /// Robot 0 along y = 0 (ids 0-14), robot 1 along y = 1 (ids 15-29), key maps every 2 m, robot
  /// 1's odometry frame rotated and moved by `T_1_world`.
  explicit Team(const Pose2& T_1_world) {
    for (int r = 0; r < 2; ++r) {
      for (int v = 0; v < 15; ++v) {
        truth.emplace_back(2.0 * v, r, 0.0);
        KeyMapNode node;
        node.robot = r;
        node.travel = 2.0 * v;
        node.T_odom_key = r == 0 ? truth.back() : T_1_world * truth.back();
        node.alignable = true;
        AppendKeyMap(&graph, std::move(node), 2.0);
      }
    }
  }
  [[nodiscard]] loop_closure::Match Closure(int i, int k) const {
    return {i, k, Between(truth[static_cast<std::size_t>(i)], truth[static_cast<std::size_t>(k)])};
  }
};

}  // namespace gridslam::pipeline::testing
