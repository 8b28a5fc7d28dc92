// The end of a Mapper run (docs/design.md §1.3, §1.7, §1.8): final optimization with pruning of
// loop edges that the optimum cannot explain (KeyMapGraph::OptimizeAndPrune), every scan's
// corrected pose from its key map, and the fused global grid of every map component.
#include <algorithm>
#include <map>

#include "gridslam/common/logging.hpp"
#include "gridslam/common/thread_scratch.hpp"
#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/grid/log_odds.hpp"
#include "gridslam/pipeline/key_map_worker.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"

namespace gridslam::pipeline {

void Mapper::Impl::FinalOptimization() {
  const auto start = std::chrono::steady_clock::now();
  const KeyMapGraph::FinalResult final_result =
      graph.OptimizeAndPrune(options.optimizer, options.graph.final_method,
                             options.graph.prune_rounds, options.loop_closure.prune_chi2);
  stats.chi2_final = final_result.chi2;
  stats.seconds_final += SecondsSince(start);
}

std::vector<TrajectoryPose> Mapper::Impl::CorrectedTrajectory(int robot, bool interpolate) const {
  const RobotState& state = robots[static_cast<std::size_t>(robot)];
  std::vector<TrajectoryPose> trajectory;
  trajectory.reserve(state.scans.size());
  // Drift correction of a key map: maps the robot's front-end frame into the map frame.
  const auto correction = [&](int id) {
    return graph.Estimate(id) * graph.node(id).T_odom_key.Inverse();
  };
  const int last = graph.LastKeyMap(robot);
  for (const ScanRecord& scan : state.scans) {
    const int id = scan.node >= 0 ? scan.node : last;
    if (id < 0) {
      trajectory.push_back({scan.time, scan.T_odom_base});
      continue;
    }
    const KeyMapNode& node = graph.node(id);
    Pose2 C = correction(id);
    if (interpolate && node.previous >= 0) {
      const KeyMapNode& previous = graph.node(node.previous);
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

std::vector<int> Mapper::Impl::ComponentNumbers() const {
  // Map components numbered 0, 1, ... in order of their lowest robot.
  std::map<int, int> component_index;
  std::vector<int> numbers;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const int root = graph.RobotComponent(static_cast<int>(r));
    const auto it = component_index.emplace(root, static_cast<int>(component_index.size())).first;
    numbers.push_back(it->second);
  }
  return numbers;
}

MapperResult Mapper::Impl::Finish() {
  for (std::size_t r = 0; r < robots.size(); ++r) {
    RobotState& state = robots[r];
    if (state.front_end == nullptr) {
      continue;  // finished before
    }
    std::optional<keymap::KeyMap> last = state.front_end->Finish();
    state.mounting = state.front_end->Mounting();
    if (last.has_value()) {
      SubmitKeyMap(static_cast<int>(r), std::move(*last), state.last_time);
    }
  }
  Sync();
  if (worker != nullptr) {
    stats.cpu_seconds_worker = worker->CpuSeconds();
    stats.seconds_caller_blocked = worker->BlockedSeconds();
    stats.seconds_worker_idle = worker->IdleSeconds();
  }
  // Nothing is matched, described or aligned any more: the fusion below holds the run's peak of
  // memory, so the front ends' windows, the cached key-map geometries and both threads' scratch
  // buffers go first (the worker's die with its thread).
  worker.reset();
  for (RobotState& state : robots) {
    state.front_end.reset();
  }
  aligner.ReleaseCache();
  ReleaseThreadScratch();
  now = front_now;
  graph.SetTime(now);
  FinalOptimization();

  MapperResult result;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    result.trajectories.push_back(
        CorrectedTrajectory(static_cast<int>(r), options.graph.interpolate_corrections));
    result.mountings.push_back(robots[r].mounting);
  }
  result.graph = graph.ActiveGraph();
  for (const KeyMapNode& node : graph.nodes()) {
    result.vertex_robot.push_back(node.robot);
  }
  result.component_of_robot = ComponentNumbers();
  int components = 0;
  for (const int c : result.component_of_robot) {
    components = std::max(components, c + 1);
  }
  const auto start = std::chrono::steady_clock::now();
  for (int c = 0; c < components; ++c) {
    if (options.fusion.method == "nearest") {
      std::vector<fusion::PosedKeyMap> posed;
      for (const KeyMapNode& node : graph.nodes()) {
        if (result.component_of_robot[static_cast<std::size_t>(node.robot)] == c) {
          posed.push_back({graph.Estimate(node.id), &node.key_map});
        }
      }
      result.maps.push_back(TiledGrid<float>::FromDense(
          fusion::FuseNearestKeyMap(posed, options.fusion), kUnknownLogOdds));
    } else {
      std::vector<fusion::PosedScan> posed;
      for (std::size_t r = 0; r < robots.size(); ++r) {
        if (result.component_of_robot[r] != c) {
          continue;
        }
        for (const FusionScan& f : robots[r].fusion_scans) {
          posed.push_back(
              {result.trajectories[r][f.scan_index].T_map_base, f.T_base_laser, &f.scan});
        }
      }
      result.maps.push_back(
          fusion::FuseScansFitting(posed, options.fusion, options.compute.Threads()));
      const double resolution = result.maps.back().Limits().Resolution();
      if (resolution != options.fusion.resolution) {
        GRIDSLAM_LOG_WARN(
            "the map spans {:.0f} m x {:.0f} m: fused at {:g} m cells instead of {:g} m (did the "
            "trajectory run away?)",
            result.maps.back().Limits().Width() * resolution,
            result.maps.back().Limits().Height() * resolution, resolution,
            options.fusion.resolution);
      }
    }
  }
  stats.seconds_fusion += SecondsSince(start);
  SyncStats();
  result.closures = graph.closures();
  result.joins = joins;
  result.stats = MergedStats();
  return result;
}

}  // namespace gridslam::pipeline
