#include "gridslam/pipeline/mapper.hpp"

#include <cmath>

#include "gridslam/grid/scan_points.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"

namespace gridslam::pipeline {

Mapper::Impl::Impl(const SlamOptions& slam_options, int num_robots)
    : options(slam_options), describer(slam_options.description) {
  GRIDSLAM_CHECK(num_robots >= 1) << num_robots;
  robots.resize(static_cast<std::size_t>(num_robots));
  for (int r = 0; r < num_robots; ++r) {
    robots[static_cast<std::size_t>(r)].front_end =
        std::make_unique<scan_matching::FrontEnd>(options.front_end);
    robots[static_cast<std::size_t>(r)].appearance =
        std::make_unique<loop_closure::AppearanceIndex>();
    robot_parent.push_back(r);
  }
  sgd = std::make_unique<pose_graph::SgdOptimizer>(options.optimizer.sgd);
}

int Mapper::Impl::FindComponent(int robot) {
  auto r = static_cast<std::size_t>(robot);
  while (robot_parent[r] != static_cast<int>(r)) {
    robot_parent[r] = robot_parent[static_cast<std::size_t>(robot_parent[r])];
    r = static_cast<std::size_t>(robot_parent[r]);
  }
  return static_cast<int>(r);
}

Eigen::Matrix3d Mapper::Impl::Information(double sigma_xy, double sigma_theta) const {
  return Eigen::Vector3d(1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_xy * sigma_xy),
                         1.0 / (sigma_theta * sigma_theta))
      .asDiagonal();
}

std::span<const Eigen::Vector2d> Mapper::Impl::RefinementPoints(const Node& b) const {
  const auto min_points = static_cast<std::size_t>(options.loop_closure.refinement.min_points);
  return b.scan_points.size() >= 2 * min_points
             ? std::span<const Eigen::Vector2d>(b.scan_points)
             : std::span<const Eigen::Vector2d>(b.description.obstacle_points);
}

void Mapper::Impl::AddFrame(int robot, const Frame& frame) {
  GRIDSLAM_CHECK(robot >= 0 && robot < static_cast<int>(robots.size())) << robot;
  RobotState& state = robots[static_cast<std::size_t>(robot)];
  now = frame.time;
  ++stats.frames;
  const auto start = std::chrono::steady_clock::now();
  scan_matching::FrontEndStep step = state.front_end->AddFrame(frame);
  stats.seconds_front_end += SecondsSince(start);
  if (state.last_pose.has_value()) {
    state.travel += (step.T_odom_base.translation() - state.last_pose->translation()).norm();
  }
  state.last_pose = step.T_odom_base;
  state.last_time = frame.time;
  state.scans.push_back({frame.time, step.T_odom_base, state.travel, -1});
  if (step.inserted || state.fusion_scans.empty()) {
    state.fusion_scans.push_back({state.scans.size() - 1, frame.T_base_laser, frame.scan});
  }
  if (step.key_map.has_value()) {
    ProcessKeyMap(robot, std::move(*step.key_map), frame.time);
  }
}

void Mapper::Impl::ProcessKeyMap(int robot, keymap::KeyMap key_map, Time time) {
  RobotState& state = robots[static_cast<std::size_t>(robot)];
  const int id = static_cast<int>(nodes.size());
  for (std::size_t s = state.unassigned; s < state.scans.size(); ++s) {
    state.scans[s].node = id;
  }
  state.unassigned = state.scans.size();
  ++stats.key_maps;

  Node node;
  node.id = id;
  node.robot = robot;
  node.previous = state.last_node;
  node.travel = state.travel;
  node.time = time;
  node.T_odom_key = key_map.T_odom_key;
  auto start = std::chrono::steady_clock::now();
  node.description = describer.Describe(key_map);
  stats.seconds_description += SecondsSince(start);
  ++stats.described;
  node.alignable = node.description.features.size() >= options.description.min_features;
  if (options.loop_closure.refinement.points == "scans") {
    for (const keymap::KeyMapScan& scan : key_map.scans) {
      const ScanPoints points =
          ExtractScanPoints(scan.scan, scan.T_base_laser, options.front_end.local_map.max_range);
      for (const Eigen::Vector2d& p : points.points) {
        node.scan_points.push_back(scan.T_key_scan * p);
      }
    }
  }
  stats.featureless += node.alignable ? 0 : 1;
  if (options.fusion.method == "nearest") {
    node.key_map = std::move(key_map);
  }
  const bool first = state.last_node < 0;
  if (first) {
    // Each robot starts in its own frame (its odometry frame), anchored until joined.
    node.estimate = node.T_odom_key;
  } else {
    const Node& previous = nodes[static_cast<std::size_t>(state.last_node)];
    node.estimate = previous.estimate * Between(previous.T_odom_key, node.T_odom_key);
  }
  nodes.push_back(std::move(node));
  uncertainty.AddNode();
  sgd->AddVertex(id, nodes.back().estimate, first);

  if (!first) {
    const Node& previous = nodes[static_cast<std::size_t>(state.last_node)];
    const Node& current = nodes.back();
    EdgeRecord edge;
    edge.from = previous.id;
    edge.to = id;
    edge.T_from_to = Between(previous.T_odom_key, current.T_odom_key);
    const double d = edge.T_from_to.translation().norm();
    const GraphOptions& g = options.graph;
    edge.information = Information(g.sequential_sigma_xy + g.sequential_sigma_xy_per_m * d,
                                   g.sequential_sigma_theta + g.sequential_sigma_theta_per_m * d);
    if (g.sequential_edges == "alignment" && previous.alignable && current.alignable) {
      start = std::chrono::steady_clock::now();
      const std::optional<Pose2> aligned = TryAlign(previous.id, id, nullptr);
      stats.seconds_alignment += SecondsSince(start);
      if (aligned.has_value() && IsApprox(*aligned, edge.T_from_to, 0.1, 0.02)) {
        edge.T_from_to = *aligned;
        ++stats.sequential_aligned;
      }
    }
    AddEdge(edge, d);
  }
  state.last_node = id;
  ++state.num_nodes;

  bool changed = false;
  large_correction_ = false;
  if (options.loop_closure.enabled && nodes.back().alignable) {
    start = std::chrono::steady_clock::now();
    changed = SearchPriorCandidates(id) || changed;
    const int every = options.loop_closure.appearance_every;
    if (every > 0 && state.num_nodes % every == 0) {
      changed = SearchAppearance(id) || changed;
    }
    stats.seconds_alignment += SecondsSince(start);
    // Spaced along the path: a place seen by dozens of overlapping key maps would otherwise fill
    // the k nearest neighbours of a query with near-duplicates and defeat the index's vote.
    if (state.travel - state.appearance_travel >= options.loop_closure.appearance_spacing) {
      state.appearance->Add(id, nodes.back().description.features.descriptors);
      state.appearance_travel = state.travel;
    }
  }
  if (large_correction_ && options.graph.optimize_large_corrections) {
    ++stats.online_full_optimizations;
    OptimizeNow();
  } else if (changed) {
    Iterate(options.graph.online_iterations);
  }
}

void Mapper::Impl::AddEdge(EdgeRecord edge, double uncertainty_weight) {
  sgd->AddEdge(edge.from, edge.to, edge.T_from_to, edge.information);
  uncertainty.AddEdge(edge.from, edge.to, uncertainty_weight);
  edges.push_back(edge);
}

void Mapper::Impl::Iterate(int iterations) {
  if (iterations <= 0) {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  sgd->Iterate(iterations);
  SyncEstimates();
  stats.seconds_optimization += SecondsSince(start);
}

void Mapper::Impl::SyncEstimates() {
  const pose_graph::PoseGraph& graph = sgd->graph();
  for (Node& node : nodes) {
    node.estimate = graph.vertex(graph.IndexOf(node.id)).T_map_v;
  }
}

void Mapper::Impl::RebuildOptimizer() {
  pose_graph::PoseGraph graph;
  std::vector<bool> anchored(robots.size(), false);
  for (const Node& node : nodes) {
    const int component = FindComponent(node.robot);
    const bool fix = !anchored[static_cast<std::size_t>(component)];
    anchored[static_cast<std::size_t>(component)] = true;
    graph.AddVertex(node.id, node.estimate, fix);
  }
  for (const EdgeRecord& edge : edges) {
    if (edge.active) {
      graph.AddEdge(edge.from, edge.to, edge.T_from_to, edge.information);
    }
  }
  sgd = std::make_unique<pose_graph::SgdOptimizer>(graph, options.optimizer.sgd);
}

Mapper::Mapper(const SlamOptions& options, int num_robots)
    : impl_(std::make_unique<Impl>(options, num_robots)) {}

Mapper::~Mapper() = default;

void Mapper::AddFrame(int robot, const Frame& frame) { impl_->AddFrame(robot, frame); }

MapperResult Mapper::Finish() { return impl_->Finish(); }

const MapperStats& Mapper::Stats() const { return impl_->stats; }

}  // namespace gridslam::pipeline
