#include "gridslam/pipeline/key_map_graph.hpp"

#include "gridslam/common/logging.hpp"
#include "gridslam/pose_graph/edge_error.hpp"

namespace gridslam::pipeline {

KeyMapGraph::KeyMapGraph(int num_robots, const pose_graph::SgdOptions& sgd)
    : sgd_options_(sgd),
      last_node_(static_cast<std::size_t>(num_robots), -1),
      num_nodes_(static_cast<std::size_t>(num_robots), 0),
      sgd_(std::make_unique<pose_graph::SgdOptimizer>(sgd)) {
  GRIDSLAM_CHECK(num_robots >= 1) << num_robots;
  for (int r = 0; r < num_robots; ++r) {
    robot_parent_.push_back(r);
  }
}

int KeyMapGraph::AddKeyMap(KeyMapNode node) {
  GRIDSLAM_CHECK(node.robot >= 0 && node.robot < num_robots()) << node.robot;
  const auto r = static_cast<std::size_t>(node.robot);
  const int id = static_cast<int>(nodes_.size());
  node.id = id;
  node.previous = last_node_[r];
  const bool first = node.previous < 0;
  // Each robot starts in its own frame (its odometry frame), anchored until joined.
  Pose2 estimate = node.T_odom_key;
  if (!first) {
    const KeyMapNode& previous = nodes_[static_cast<std::size_t>(node.previous)];
    estimate = estimates_[static_cast<std::size_t>(node.previous)] *
               Between(previous.T_odom_key, node.T_odom_key);
  }
  nodes_.push_back(std::move(node));
  estimates_.push_back(estimate);
  uncertainty_.AddNode();
  sgd_->AddVertex(id, estimate, first);
  last_node_[r] = id;
  ++num_nodes_[r];
  events_.push_back({MapperEvent::Kind::kKeyMapAdded, now_, static_cast<int>(r), -1, id});
  return id;
}

void KeyMapGraph::AddEdge(const EdgeRecord& edge, double uncertainty_weight) {
  GRIDSLAM_CHECK(edge.from >= 0 && edge.from < size() && edge.to >= 0 && edge.to < size())
      << edge.from << " " << edge.to;
  sgd_->AddEdge(edge.from, edge.to, edge.T_from_to, edge.information);
  uncertainty_.AddEdge(edge.from, edge.to, uncertainty_weight);
  edges_.push_back(edge);
}

int KeyMapGraph::RecordClosure(const loop_closure::Match& match, ClosureOutcome outcome,
                               bool appearance) {
  closures_.push_back({match.i, match.k, match.T_i_k, outcome, appearance});
  ++outcome_counts_[static_cast<std::size_t>(outcome)];
  const int index = static_cast<int>(closures_.size()) - 1;
  if (outcome == ClosureOutcome::kGated) {
    gated_records_[PairKey(match.i, match.k)].push_back(index);
  }
  return index;
}

int KeyMapGraph::AddLoopEdge(const loop_closure::Match& match, ClosureOutcome outcome,
                             bool appearance, const Eigen::Matrix3d& information,
                             double uncertainty_weight) {
  GRIDSLAM_CHECK(outcome == ClosureOutcome::kAccepted || outcome == ClosureOutcome::kJoined);
  EdgeRecord edge;
  edge.from = match.i;
  edge.to = match.k;
  edge.T_from_to = match.T_i_k;
  edge.information = information;
  edge.loop = true;
  edge.closure = RecordClosure(match, outcome, appearance);
  AddEdge(edge, uncertainty_weight);
  ++loop_edges_added_;
  events_.push_back({MapperEvent::Kind::kClosureAccepted, now_, Robot(match.i), Robot(match.k),
                     match.i, match.k, edge.closure});
  return edge.closure;
}

void KeyMapGraph::AcceptGated(const loop_closure::Match& match, const Eigen::Matrix3d& information,
                              double uncertainty_weight) {
  EdgeRecord edge;
  edge.from = match.i;
  edge.to = match.k;
  edge.T_from_to = match.T_i_k;
  edge.information = information;
  edge.loop = true;
  // Every record of the pair still gated (in the order recorded) becomes accepted.
  if (const auto it = gated_records_.find(PairKey(edge.from, edge.to));
      it != gated_records_.end()) {
    for (const int c : it->second) {
      if (closures_[static_cast<std::size_t>(c)].outcome == ClosureOutcome::kGated) {
        SetOutcome(c, ClosureOutcome::kAccepted);
        edge.closure = c;
      }
    }
    gated_records_.erase(it);
  }
  AddEdge(edge, uncertainty_weight);
  ++loop_edges_added_;
  events_.push_back({MapperEvent::Kind::kClosureAccepted, now_, Robot(match.i), Robot(match.k),
                     match.i, match.k, edge.closure});
}

void KeyMapGraph::SetOutcome(int closure, ClosureOutcome outcome) {
  ClosureRecord& record = closures_[static_cast<std::size_t>(closure)];
  --outcome_counts_[static_cast<std::size_t>(record.outcome)];
  record.outcome = outcome;
  ++outcome_counts_[static_cast<std::size_t>(outcome)];
}

long KeyMapGraph::NumClosures(ClosureOutcome outcome) const {
  return outcome_counts_[static_cast<std::size_t>(outcome)];
}

void KeyMapGraph::Iterate(int iterations) {
  if (iterations <= 0) {
    return;
  }
  sgd_->Iterate(iterations);
  SyncEstimates(sgd_->graph());
}

void KeyMapGraph::Optimize(const pose_graph::OptimizerOptions& options) {
  RebuildOptimizer();
  pose_graph::PoseGraph graph = sgd_->graph();
  pose_graph::Optimize(graph, options);
  SyncEstimates(graph);
  RebuildOptimizer();
}

void KeyMapGraph::MergeComponents(int robot_a, int robot_b, const Pose2& T_a_b, Time time) {
  const int component_a = RobotComponent(robot_a);
  const int component_b = RobotComponent(robot_b);
  GRIDSLAM_CHECK(component_a != component_b) << robot_a << " " << robot_b;
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    if (RobotComponent(nodes_[id].robot) == component_b) {
      estimates_[id] = T_a_b * estimates_[id];
    }
  }
  robot_parent_[static_cast<std::size_t>(component_b)] = component_a;
  RebuildOptimizer();  // one anchor for the merged component
  events_.push_back({MapperEvent::Kind::kRobotsJoined, time, robot_a, robot_b});
}

KeyMapGraph::FinalResult KeyMapGraph::OptimizeAndPrune(const pose_graph::OptimizerOptions& options,
                                                       const std::string& method, int prune_rounds,
                                                       double prune_chi2) {
  FinalResult result;
  for (int round = 0;; ++round) {
    RebuildOptimizer();  // graph with the current estimates, active edges, one anchor each
    pose_graph::PoseGraph graph = sgd_->graph();
    if (method != "none") {
      pose_graph::OptimizerOptions optimizer = options;
      optimizer.method = method;
      pose_graph::Optimize(graph, optimizer);
    }
    SyncEstimates(graph);
    result.chi2 = pose_graph::Chi2(graph);
    if (round == prune_rounds) {
      break;
    }
    // The loop edge the optimum explains worst, if above the threshold, is removed.
    int edge_index = 0;
    int worst = -1;
    double worst_chi2 = prune_chi2;
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      if (!edges_[e].active) {
        continue;
      }
      if (edges_[e].loop) {
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
    EdgeRecord& removed = edges_[static_cast<std::size_t>(worst)];
    removed.active = false;
    if (removed.closure >= 0) {
      SetOutcome(removed.closure, ClosureOutcome::kPruned);
    }
    ++result.pruned;
    events_.push_back({MapperEvent::Kind::kClosureRemoved, now_, Robot(removed.from),
                       Robot(removed.to), removed.from, removed.to, removed.closure});
  }
  RebuildOptimizer();
  return result;
}

Pose2 KeyMapGraph::Estimate(int id) const {
  GRIDSLAM_CHECK(id >= 0 && id < size()) << id;
  return estimates_[static_cast<std::size_t>(id)];
}

int KeyMapGraph::RobotComponent(int robot) const {
  auto r = static_cast<std::size_t>(robot);
  while (robot_parent_[r] != static_cast<int>(r)) {
    r = static_cast<std::size_t>(robot_parent_[r]);
  }
  return static_cast<int>(r);
}

std::vector<MapperEvent> KeyMapGraph::DrainEvents() {
  std::vector<MapperEvent> events;
  events.swap(events_);
  return events;
}

void KeyMapGraph::RebuildOptimizer() {
  pose_graph::PoseGraph graph;
  std::vector<bool> anchored(robot_parent_.size(), false);
  for (const KeyMapNode& node : nodes_) {
    const auto component = static_cast<std::size_t>(RobotComponent(node.robot));
    graph.AddVertex(node.id, estimates_[static_cast<std::size_t>(node.id)], !anchored[component]);
    anchored[component] = true;
  }
  for (const EdgeRecord& edge : edges_) {
    if (edge.active) {
      graph.AddEdge(edge.from, edge.to, edge.T_from_to, edge.information);
    }
  }
  sgd_ = std::make_unique<pose_graph::SgdOptimizer>(graph, sgd_options_);
}

void KeyMapGraph::SyncEstimates(const pose_graph::PoseGraph& graph) {
  for (const KeyMapNode& node : nodes_) {
    estimates_[static_cast<std::size_t>(node.id)] = graph.vertex(graph.IndexOf(node.id)).T_map_v;
  }
}

}  // namespace gridslam::pipeline
