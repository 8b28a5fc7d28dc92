// The end of a Mapper run (DESIGN.md §1.3, §1.7, §1.8): final optimization with pruning of loop
// edges that the optimum cannot explain, every scan's corrected pose from its key map, and the
// fused global grid of every map component.
#include <algorithm>
#include <map>

#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"
#include "gridslam/pose_graph/edge_error.hpp"
#include "gridslam/pose_graph/optimizer.hpp"

namespace gridslam::pipeline {

void Mapper::Impl::FinalOptimization() {
  const auto start = std::chrono::steady_clock::now();
  // Optimize, prune the worst loop edge, and again, up to prune_rounds prunings; the graph is
  // optimized once more after the last pruning, so that the result (and chi2_final) is the
  // optimum of exactly the edges that remain.
  for (int round = 0;; ++round) {
    RebuildOptimizer();  // graph with the current estimates, active edges, one anchor each
    pose_graph::PoseGraph graph = sgd->graph();
    if (options.graph.final_method != "none") {
      pose_graph::OptimizerOptions optimizer = options.optimizer;
      optimizer.method = options.graph.final_method;
      pose_graph::Optimize(graph, optimizer);
    }
    for (Node& node : nodes) {
      node.estimate = graph.vertex(graph.IndexOf(node.id)).T_map_v;
    }
    stats.chi2_final = pose_graph::Chi2(graph);
    if (round == options.graph.prune_rounds) {
      break;
    }
    // Loop edges the optimum cannot explain are removed, the worst first.
    int edge_index = 0;
    int worst = -1;
    double worst_chi2 = options.loop_closure.prune_chi2;
    std::vector<int> active_to_record;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (!edges[e].active) {
        continue;
      }
      if (edges[e].loop) {
        const double chi2 = pose_graph::EdgeChi2(graph, edge_index);
        if (chi2 > worst_chi2) {
          worst_chi2 = chi2;
          worst = static_cast<int>(e);
        }
      }
      ++edge_index;
    }
    if (worst < 0) {
      break;
    }
    // Remove every loop edge above the threshold when it is far above, else only the worst.
    edges[static_cast<std::size_t>(worst)].active = false;
    const int closure = edges[static_cast<std::size_t>(worst)].closure;
    if (closure >= 0) {
      closures[static_cast<std::size_t>(closure)].outcome = "pruned";
    }
    ++stats.pruned;
  }
  RebuildOptimizer();
  stats.seconds_final += SecondsSince(start);
}

std::vector<TrajectoryPose> Mapper::Impl::CorrectedTrajectory(int robot) const {
  const RobotState& state = robots[static_cast<std::size_t>(robot)];
  std::vector<TrajectoryPose> trajectory;
  trajectory.reserve(state.scans.size());
  // Drift correction of a key map: maps the robot's front-end frame into the map frame.
  const auto correction = [&](int id) {
    const Node& n = nodes[static_cast<std::size_t>(id)];
    return n.estimate * n.T_odom_key.Inverse();
  };
  for (const ScanRecord& scan : state.scans) {
    const int id = scan.node >= 0 ? scan.node : state.last_node;
    if (id < 0) {
      trajectory.push_back({scan.time, scan.T_odom_base});
      continue;
    }
    const Node& node = nodes[static_cast<std::size_t>(id)];
    Pose2 C = correction(id);
    if (options.graph.interpolate_corrections && node.previous >= 0) {
      const Node& previous = nodes[static_cast<std::size_t>(node.previous)];
      const double span = node.travel - previous.travel;
      if (span > 1e-6) {
        const double alpha = std::clamp((scan.travel - previous.travel) / span, 0.0, 1.0);
        C = Interpolate(correction(node.previous), C, alpha);
      }
    }
    trajectory.push_back({scan.time, C * scan.T_odom_base});
  }
  return trajectory;
}

MapperResult Mapper::Impl::Finish() {
  for (std::size_t r = 0; r < robots.size(); ++r) {
    RobotState& state = robots[r];
    std::optional<keymap::KeyMap> last = state.front_end->Finish();
    if (last.has_value()) {
      ProcessKeyMap(static_cast<int>(r), std::move(*last), state.last_time);
    }
  }
  FinalOptimization();

  MapperResult result;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    result.trajectories.push_back(CorrectedTrajectory(static_cast<int>(r)));
  }
  result.graph = sgd->graph();
  for (const Node& node : nodes) {
    result.vertex_robot.push_back(node.robot);
  }
  // Map components numbered 0, 1, ... in order of their lowest robot.
  std::map<int, int> component_index;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const int root = FindComponent(static_cast<int>(r));
    const auto it = component_index.emplace(root, static_cast<int>(component_index.size())).first;
    result.component_of_robot.push_back(it->second);
  }
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t c = 0; c < component_index.size(); ++c) {
    if (options.fusion.method == "nearest") {
      std::vector<fusion::PosedKeyMap> posed;
      for (const Node& node : nodes) {
        if (result.component_of_robot[static_cast<std::size_t>(node.robot)] ==
            static_cast<int>(c)) {
          posed.push_back({node.estimate, &node.key_map});
        }
      }
      result.maps.push_back(fusion::FuseNearestKeyMap(posed, options.fusion));
    } else {
      std::vector<fusion::PosedScan> posed;
      for (std::size_t r = 0; r < robots.size(); ++r) {
        if (result.component_of_robot[r] != static_cast<int>(c)) {
          continue;
        }
        for (const FusionScan& f : robots[r].fusion_scans) {
          posed.push_back(
              {result.trajectories[r][f.scan_index].T_map_base, f.T_base_laser, &f.scan});
        }
      }
      result.maps.push_back(fusion::FuseScans(posed, options.fusion));
    }
  }
  stats.seconds_fusion += SecondsSince(start);
  result.closures = closures;
  result.joins = joins;
  result.stats = stats;
  return result;
}

}  // namespace gridslam::pipeline
