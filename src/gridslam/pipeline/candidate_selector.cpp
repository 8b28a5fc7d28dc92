#include "gridslam/pipeline/candidate_selector.hpp"

#include <algorithm>
#include <cmath>

namespace gridslam::pipeline {

std::vector<int> CandidateSelector::Choose(std::vector<Candidate> candidates,
                                           const KeyMapGraph& graph) const {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.node < b.node);
  });
  std::vector<int> chosen;
  for (const Candidate& c : candidates) {
    if (static_cast<int>(chosen.size()) >= options_.max_candidates) {
      break;
    }
    const KeyMapNode& node = graph.node(c.node);
    const bool too_close = std::any_of(chosen.begin(), chosen.end(), [&](int other) {
      const KeyMapNode& o = graph.node(other);
      return o.robot == node.robot && std::abs(o.travel - node.travel) < options_.candidate_spacing;
    });
    if (!too_close) {
      chosen.push_back(c.node);
    }
  }
  return chosen;
}

std::vector<int> CandidateSelector::Prior(const KeyMapGraph& graph, int k,
                                          const std::vector<double>& distance) const {
  const KeyMapNode& current = graph.node(k);
  const Pose2 X_k = graph.Estimate(k);
  const int component = graph.Component(k);
  std::vector<Candidate> candidates;
  for (const KeyMapNode& node : graph.nodes()) {
    if (node.id == k || !node.alignable || graph.Component(node.id) != component) {
      continue;
    }
    if (node.robot == current.robot && current.travel - node.travel < options_.min_travel_gap) {
      continue;
    }
    const double u = distance[static_cast<std::size_t>(node.id)];
    if (!std::isfinite(u)) {
      continue;
    }
    const double d = Between(graph.Estimate(node.id), X_k).translation().norm();
    const double radius = std::min(options_.max_search_radius,
                                   options_.search_radius + options_.search_radius_per_m * u);
    if (d < radius) {
      candidates.push_back({d, node.id});
    }
  }
  return Choose(std::move(candidates), graph);
}

std::vector<int> CandidateSelector::CatchUp(const KeyMapGraph& graph, int b,
                                            const std::vector<bool>& moved) const {
  const Eigen::Vector2d centre = graph.Estimate(b).translation();
  std::vector<Candidate> candidates;
  for (const KeyMapNode& a : graph.nodes()) {
    const double d = (graph.Estimate(a.id).translation() - centre).norm();
    if (!moved[static_cast<std::size_t>(a.robot)] && a.alignable &&
        d < options_.max_search_radius) {
      candidates.push_back({d, a.id});
    }
  }
  return Choose(std::move(candidates), graph);
}

}  // namespace gridslam::pipeline
