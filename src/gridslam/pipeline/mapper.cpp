#include "gridslam/pipeline/mapper.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "gridslam/grid/scan_points.hpp"
#include "gridslam/pipeline/key_map_worker.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"

namespace gridslam::pipeline {

namespace {

// Key maps queued for the worker at most. Loop closures come in bursts, and so do key maps (fast
// motion): a queue of a few would leave one thread idle while the other catches up.
constexpr std::size_t kMaxQueuedKeyMaps = 32;
// The caller describes a queued key map when this many wait undescribed (the worker is behind).
constexpr std::size_t kHelpBacklog = 3;

}  // namespace

int ComputeOptions::Threads() const {
  if (threads > 0) {
    return threads;
  }
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 2);
}

Mapper::Impl::Impl(const MapperOptions& mapper_options, int num_robots)
    : options(mapper_options),
      describer(mapper_options.description),
      graph(num_robots, mapper_options.optimizer.sgd),
      aligner(graph, mapper_options.matching, mapper_options.loop_closure,
              mapper_options.compute.key_map_cache),
      selector(mapper_options.loop_closure),
      arbiter(mapper_options.loop_closure),
      joiner(mapper_options.loop_closure, mapper_options.graph.loop_uncertainty,
             mapper_options.optimizer),
      join_verifier(mapper_options.loop_closure),
      snapshots(mapper_options.fusion),
      appearance_rng(loop_closure::AppearanceIndex::NewRandomState()) {
  GRIDSLAM_CHECK(num_robots >= 1) << num_robots;
  robots.resize(static_cast<std::size_t>(num_robots));
  for (RobotState& robot : robots) {
    robot.front_end = std::make_unique<scan_matching::FrontEnd>(options.front_end);
    robot.appearance = std::make_unique<loop_closure::AppearanceIndex>(
        loop_closure::AppearanceIndex::kDefaultBlockSize,
        loop_closure::AppearanceIndex::kDefaultRatio, appearance_rng);
  }
  if (options.compute.Threads() >= 2) {
    // Key maps may wait while the worker closes loops: each holds its grid (0.4 MB at the
    // defaults) and, once described, its description.
    worker = std::make_unique<KeyMapWorker>(
        [this](KeyMapJob& job) { IntegrateKeyMap(job); },
        [this](KeyMapJob& job) { job.described = Describe(job.key_map); }, kMaxQueuedKeyMaps);
  }
}

Mapper::Impl::~Impl() = default;

void Mapper::Impl::Sync() {
  if (worker != nullptr) {
    worker->Drain();
  }
}

MapperStats Mapper::Impl::MergedStats() const {
  MapperStats merged = stats;
  merged.frames = front_stats.frames;
  merged.odometry_doubtful = front_stats.odometry_doubtful;
  merged.odometry_missing = front_stats.odometry_missing;
  merged.odometry_overruled = front_stats.odometry_overruled;
  merged.wide_searches = front_stats.wide_searches;
  merged.poor_matches = front_stats.poor_matches;
  merged.poor_rescued = front_stats.poor_rescued;
  merged.poor_ambiguous = front_stats.poor_ambiguous;
  merged.degenerate_one = front_stats.degenerate_one;
  merged.degenerate_both = front_stats.degenerate_both;
  merged.far_matches = front_stats.far_matches;
  merged.wall_normal_frames = front_stats.wall_normal_frames;
  merged.seconds_front_end = front_stats.seconds_front_end;
  return merged;
}

void Mapper::Impl::AddFrame(int robot, const Frame& frame) {
  GRIDSLAM_CHECK(robot >= 0 && robot < static_cast<int>(robots.size())) << robot;
  RobotState& state = robots[static_cast<std::size_t>(robot)];
  GRIDSLAM_CHECK(state.front_end != nullptr) << "Mapper::AddFrame after Finish";
  front_now = frame.time;
  MapperStats& fs = front_stats;
  ++fs.frames;
  const auto start = std::chrono::steady_clock::now();
  scan_matching::FrontEndStep step = state.front_end->AddFrame(frame);
  fs.seconds_front_end += SecondsSince(start);
  fs.odometry_doubtful += step.odometry == scan_matching::OdometryCheck::kDoubtful ? 1 : 0;
  fs.odometry_missing += step.odometry == scan_matching::OdometryCheck::kMissing ? 1 : 0;
  fs.odometry_overruled += step.odometry_overruled ? 1 : 0;
  fs.wide_searches += step.wide_search ? 1 : 0;
  fs.poor_matches += step.poor_match ? 1 : 0;
  fs.poor_rescued += step.rescue == scan_matching::RescueVerdict::kRescued ? 1 : 0;
  fs.poor_ambiguous += step.rescue == scan_matching::RescueVerdict::kAmbiguous ? 1 : 0;
  fs.wall_normal_frames += step.wall_normals ? 1 : 0;
  if (step.status == scan_matching::FrameStatus::kMatched) {
    fs.degenerate_one += step.match.degeneracy.degenerate_directions == 1 ? 1 : 0;
    fs.degenerate_both += step.match.degeneracy.degenerate_directions == 2 ? 1 : 0;
    fs.far_matches += step.match.far_window ? 1 : 0;
  }
  if (state.last_pose.has_value()) {
    state.travel += (step.T_odom_base.translation() - state.last_pose->translation()).norm();
  }
  state.last_pose = step.T_odom_base;
  state.last_odometry = frame.has_odometry ? frame.T_odom_base : step.T_odom_base;
  state.last_time = frame.time;
  state.scans.push_back({frame.time, step.T_odom_base, state.travel, -1});
  if (step.inserted || state.fusion_scans.empty()) {
    state.fusion_scans.push_back({state.scans.size() - 1, frame.T_base_laser, frame.scan});
  }
  if (step.key_map.has_value()) {
    SubmitKeyMap(robot, std::move(*step.key_map), frame.time);
  }
}

void Mapper::Impl::SubmitKeyMap(int robot, keymap::KeyMap key_map, Time time) {
  RobotState& state = robots[static_cast<std::size_t>(robot)];
  KeyMapJob job;
  job.robot = robot;
  job.id = key_maps_made++;
  for (std::size_t s = state.unassigned; s < state.scans.size(); ++s) {
    state.scans[s].node = job.id;
  }
  state.unassigned = state.scans.size();
  job.time = time;
  job.event_time = front_now;
  job.travel = state.travel;
  job.key_map = std::move(key_map);
  if (worker == nullptr) {
    IntegrateKeyMap(job);
    return;
  }
  // The worker integrates; the description goes to whichever thread is free: the worker, unless
  // key maps pile up undescribed (then this thread describes the newest).
  worker->Push(std::move(job));
  worker->Help(kHelpBacklog);
}

DescribedKeyMap Mapper::Impl::Describe(const keymap::KeyMap& key_map) const {
  const auto start = std::chrono::steady_clock::now();
  DescribedKeyMap described;
  described.description = describer.Describe(key_map);
  if (options.loop_closure.refinement.points == "scans") {
    for (const keymap::KeyMapScan& scan : key_map.scans) {
      const ScanReturns points =
          ExtractScanReturns(scan.scan, scan.T_base_laser, options.front_end.local_map.max_range);
      const PointTransform to_key(scan.T_key_scan);
      for (const Eigen::Vector2d& p : points.points) {
        described.scan_points.push_back(to_key(p));
      }
    }
  }
  described.seconds = SecondsSince(start);
  return described;
}

void Mapper::Impl::IntegrateKeyMap(KeyMapJob& job) {
  const int robot = job.robot;
  RobotState& state = robots[static_cast<std::size_t>(robot)];
  now = job.event_time;
  graph.SetTime(now);
  const int id = graph.size();
  GRIDSLAM_CHECK(id == job.id) << id << " " << job.id;
  ++stats.key_maps;

  if (!job.described.has_value()) {
    job.described = Describe(job.key_map);
  }
  DescribedKeyMap& described = *job.described;
  stats.seconds_description += described.seconds;
  ++stats.described;
  KeyMapNode node;
  node.robot = robot;
  node.travel = job.travel;
  node.time = job.time;
  node.T_odom_key = job.key_map.T_odom_key;
  node.features = std::move(described.description.features);
  node.cells = std::move(described.description.cells);
  node.alignable = node.features.size() >= options.description.min_features;
  // The distance field and obstacle points are not kept with the node (they follow from its
  // cells); the aligner's cache holds the recent ones.
  aligner.Remember(id, {std::move(described.description.distance),
                        std::move(described.description.obstacle_points)});
  node.scan_points = std::move(described.scan_points);
  stats.featureless += node.alignable ? 0 : 1;
  if (options.fusion.method == "nearest") {
    node.key_map = std::move(job.key_map);
  }
  auto start = std::chrono::steady_clock::now();
  const int previous = graph.LastKeyMap(robot);
  GRIDSLAM_CHECK(graph.AddKeyMap(std::move(node)) == id);

  if (previous >= 0) {
    const KeyMapNode& before = graph.node(previous);
    const KeyMapNode& current = graph.node(id);
    EdgeRecord edge;
    edge.from = previous;
    edge.to = id;
    edge.T_from_to = Between(before.T_odom_key, current.T_odom_key);
    const double d = edge.T_from_to.translation().norm();
    const GraphOptions& g = options.graph;
    edge.information = Information(g.sequential_sigma_xy + g.sequential_sigma_xy_per_m * d,
                                   g.sequential_sigma_theta + g.sequential_sigma_theta_per_m * d);
    if (g.sequential_edges == "alignment" && before.alignable && current.alignable) {
      start = std::chrono::steady_clock::now();
      const std::optional<Alignment> aligned = aligner.Align(previous, id, nullptr, 0.0);
      stats.seconds_alignment += SecondsSince(start);
      if (aligned.has_value() && IsApprox(aligned->T_i_k, edge.T_from_to, 0.1, 0.02)) {
        edge.T_from_to = aligned->T_i_k;
        ++stats.sequential_aligned;
      }
    }
    graph.AddEdge(edge, d);
  }

  bool changed = false;
  bool large_correction = false;
  if (options.loop_closure.enabled && graph.node(id).alignable) {
    start = std::chrono::steady_clock::now();
    const PriorSearch prior = SearchPriorCandidates(id);
    changed = prior.changed;
    large_correction = prior.large_correction;
    const int every = options.loop_closure.appearance_every;
    if (every > 0 && graph.NumKeyMaps(robot) % every == 0) {
      changed = SearchAppearance(id, prior.tried) || changed;
    }
    RetryLoopHypothesis(id);
    stats.seconds_alignment += SecondsSince(start);
    // Spaced along the path: a place seen by dozens of overlapping key maps would otherwise fill
    // the k nearest neighbours of a query with near-duplicates and defeat the index's vote.
    if (job.travel - state.appearance_travel >= options.loop_closure.appearance_spacing) {
      state.appearance->Add(id, graph.node(id).features.descriptors);
      state.appearance_travel = job.travel;
    }
  }
  if (large_correction && options.graph.optimize_large_corrections) {
    ++stats.online_full_optimizations;
    OptimizeNow();
  } else if (changed) {
    Iterate(options.graph.online_iterations);
  }
  SyncStats();
}

void Mapper::Impl::Iterate(int iterations) {
  const auto start = std::chrono::steady_clock::now();
  graph.Iterate(iterations);
  stats.seconds_optimization += SecondsSince(start);
}

void Mapper::Impl::OptimizeNow() {
  const auto start = std::chrono::steady_clock::now();
  graph.Optimize(options.optimizer);
  stats.seconds_optimization += SecondsSince(start);
}

void Mapper::Impl::SyncStats() {
  const AlignerCounters& counters = aligner.counters();
  stats.verified = counters.verified;
  stats.prior_refined = counters.prior_refined;
  stats.prior_searches = counters.prior_searches;
  stats.prior_wide_searches = counters.prior_wide_searches;
  stats.prior_wide_found = counters.prior_wide_found;
  stats.prior_ridges = counters.prior_ridges;
  stats.prior_weak_by_search = counters.prior_weak_by_search;
  stats.geometry_recomputed = counters.geometry_recomputed;
  stats.window_refinements = counters.window_refinements;
  stats.window_refined = counters.window_refined;
  stats.accepted = graph.loop_edges_added();
  stats.rejected_gate = graph.NumClosures(ClosureOutcome::kGated);
  stats.pruned = graph.NumClosures(ClosureOutcome::kPruned);
  stats.joins = static_cast<long>(joins.size());
}

Pose2 Mapper::Impl::MapToFrontEnd(int robot) const {
  const int last = graph.LastKeyMap(robot);
  if (last < 0) {
    return Pose2();
  }
  return graph.Estimate(last) * graph.node(last).T_odom_key.Inverse();
}

MapSnapshot Mapper::Impl::Snapshot() {
  MapSnapshot snapshot;
  Sync();
  snapshot.time = front_now;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    snapshot.trajectories.push_back(
        CorrectedTrajectory(static_cast<int>(r), options.graph.interpolate_corrections));
  }
  snapshot.component_of_robot = ComponentNumbers();
  // Key maps whose scans are complete enter the incremental fusion once.
  for (RobotState& state : robots) {
    while (state.unfused < state.fusion_scans.size()) {
      const int id = state.scans[state.fusion_scans[state.unfused].scan_index].node;
      if (id < 0) {
        break;  // after the robot's newest key map
      }
      const Pose2 T_key_odom = graph.node(id).T_odom_key.Inverse();
      std::vector<fusion::PosedScan> posed;
      for (; state.unfused < state.fusion_scans.size(); ++state.unfused) {
        const FusionScan& f = state.fusion_scans[state.unfused];
        if (state.scans[f.scan_index].node != id) {
          break;
        }
        posed.push_back(
            {T_key_odom * state.scans[f.scan_index].T_odom_base, f.T_base_laser, &f.scan});
      }
      snapshots.AddKeyMap(id, posed);
    }
  }
  int components = 0;
  for (const int c : snapshot.component_of_robot) {
    components = std::max(components, c + 1);
  }
  SnapshotFusion::UpdateStats update;
  for (int c = 0; c < components; ++c) {
    std::vector<SnapshotFusion::Placed> placed;
    for (const KeyMapNode& node : graph.nodes()) {
      if (snapshot.component_of_robot[static_cast<std::size_t>(node.robot)] == c) {
        placed.push_back({node.id, graph.Estimate(node.id)});
      }
    }
    snapshot.maps.push_back(snapshots.Update(c, placed, update));
  }
  snapshot.key_maps_added = update.added;
  snapshot.key_maps_replaced = update.replaced;
  return snapshot;
}

Mapper::Mapper(const MapperOptions& options, int num_robots)
    : impl_(std::make_unique<Impl>(options, num_robots)) {}

Mapper::~Mapper() = default;

void Mapper::AddFrame(int robot, const Frame& frame) { impl_->AddFrame(robot, frame); }

MapperResult Mapper::Finish() { return impl_->Finish(); }

const MapperStats& Mapper::Stats() const {
  impl_->Sync();
  impl_->reported = impl_->MergedStats();
  return impl_->reported;
}

std::optional<Pose2> Mapper::CurrentPose(int robot) const {
  impl_->Sync();
  const RobotState& state = impl_->robots.at(static_cast<std::size_t>(robot));
  if (!state.last_pose.has_value()) {
    return std::nullopt;
  }
  return impl_->MapToFrontEnd(robot) * *state.last_pose;
}

Pose2 Mapper::MapToOdom(int robot) const {
  const std::optional<Pose2> pose = CurrentPose(robot);
  if (!pose.has_value()) {
    return Pose2();
  }
  return *pose * impl_->robots[static_cast<std::size_t>(robot)].last_odometry.Inverse();
}

int Mapper::MapComponent(int robot) const {
  impl_->Sync();
  return impl_->ComponentNumbers().at(static_cast<std::size_t>(robot));
}

MapSnapshot Mapper::Snapshot() { return impl_->Snapshot(); }

std::vector<MapperEvent> Mapper::DrainEvents() {
  impl_->Sync();
  return impl_->graph.DrainEvents();
}

}  // namespace gridslam::pipeline
