// The global appearance search of the Mapper (DESIGN.md §1.6, §1.9; issues 7, 8): a new key map
// is looked up in every robot's key maps, its own robot's included (each robot has its own index,
// mapper.cpp), with no prior: a robot whose drift outgrew the prior-based candidate search still
// closes its loop, and robots with unknown relative starts find each other. Then the
// join of two robots' graphs once min_join_matches mutually consistent verified matches exist
// (before that each graph is anchored on its own: Howard et al. 2006's manifold, where the
// shared places simply exist twice), a catch-up search that links the key maps the two robots
// built before they met, and appearance matches within one map (one robot's or joined robots'),
// which keep their maps tied together where the estimate has drifted too far
// for the prior-based candidates of mapper_closures.cpp: a match that agrees with the estimate
// is a loop edge at once, one that does not waits for independent matches that agree with it.
#include <algorithm>
#include <cmath>

#include "gridslam/common/logging.hpp"
#include "gridslam/pipeline/mapper_internal.hpp"
#include "gridslam/pose_graph/optimizer.hpp"

namespace gridslam::pipeline {
namespace {

const Node& At(const std::vector<Node>& nodes, int id) {
  return nodes[static_cast<std::size_t>(id)];
}

// Two matches between the same two robots (or components) agree when the loop they form with
// each side's own map (a.i -> a.k measured, a.k -> b.k and b.i -> a.i by the estimates) closes;
// the tolerance grows with the distance the loop spans on each side, whose drift it contains.
bool PairConsistent(const PendingJoin& a, const PendingJoin& b, const std::vector<Node>& nodes,
                    const loop_closure::LoopClosureOptions& lc) {
  const Pose2 loop = a.T_i_k * Between(At(nodes, a.k).estimate, At(nodes, b.k).estimate) *
                     b.T_i_k.Inverse() * Between(At(nodes, b.i).estimate, At(nodes, a.i).estimate);
  const double span = std::max(
      (At(nodes, a.k).estimate.translation() - At(nodes, b.k).estimate.translation()).norm(),
      (At(nodes, a.i).estimate.translation() - At(nodes, b.i).estimate.translation()).norm());
  return loop.translation().norm() < lc.pairwise_xy + lc.gate_xy_per_m * span &&
         std::abs(loop.theta()) < lc.pairwise_theta + lc.gate_theta_per_m * span;
}

/// Independent evidence: the matched key maps of `a` and `b` lie apart along both paths (an
/// aliased place matches a run of neighbouring key maps, all consistently).
bool Independent(const PendingJoin& a, const PendingJoin& b, const std::vector<Node>& nodes,
                 double travel) {
  return std::abs(At(nodes, a.i).travel - At(nodes, b.i).travel) >= travel &&
         std::abs(At(nodes, a.k).travel - At(nodes, b.k).travel) >= travel;
}

/// `stored` oriented from the group of `from` to the group of `to` (group = robot or
/// component, given by `group`), or nullopt if it links other groups.
template <class Group>
std::optional<PendingJoin> Oriented(const PendingJoin& stored, int from, int to, Group group) {
  const int gi = group(stored.i);
  const int gk = group(stored.k);
  if (gi == from && gk == to) {
    return stored;
  }
  if (gi == to && gk == from) {
    return PendingJoin{stored.k, stored.i, stored.T_i_k.Inverse()};
  }
  return std::nullopt;
}

}  // namespace

bool Mapper::Impl::SearchAppearance(int k) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const Node& current = At(nodes, k);
  const int component = FindComponent(current.robot);
  const auto component_of = [&](int id) { return FindComponent(At(nodes, id).robot); };
  ++stats.appearance_queries;
  std::vector<double> distance;  // uncertainty distances from k, computed when first needed
  bool changed = false;
  // Every robot is searched in its own index: the query's nearest neighbours are that robot's
  // key maps, not near-duplicates from another one. In the query's own robot, the key maps just
  // behind it (min_travel_gap) and the prior-based candidates already tried are left out.
  const auto allowed_in = [&](std::size_t r) {
    return [&, r](int id) {
      if (static_cast<int>(r) != current.robot) {
        return true;
      }
      return current.travel - At(nodes, id).travel >= lc.min_travel_gap &&
             std::find(prior_tried.begin(), prior_tried.end(), id) == prior_tried.end();
    };
  };
  for (std::size_t r = 0; r < robots.size(); ++r) {
    if (robots[r].num_nodes == 0) {
      continue;
    }
    const auto votes =
        robots[r].appearance->Query(current.description.features.descriptors,
                                    lc.appearance_candidates, /*min_votes=*/5, allowed_in(r));
    for (const loop_closure::AppearanceVote& vote : votes) {
      ++stats.appearance_candidates;
      const std::optional<Pose2> measured = TryAlign(vote.node, k, nullptr);
      if (!measured.has_value()) {
        continue;
      }
      if (FindComponent(static_cast<int>(r)) == component) {
        changed = AcceptAcrossRobots(vote.node, k, *measured, distance) || changed;
        continue;
      }
      closures.push_back({vote.node, k, *measured, "pending", true});
      const PendingJoin match{vote.node, k, *measured};
      const int other = component_of(vote.node);
      std::vector<PendingJoin> consistent = {match};
      for (const PendingJoin& stored : pending) {
        // A match found from the other side (the other robot's query) counts reversed.
        const std::optional<PendingJoin> p = Oriented(stored, other, component, component_of);
        if (p.has_value() && Independent(match, *p, nodes, lc.independent_travel) &&
            PairConsistent(match, *p, nodes, lc)) {
          consistent.push_back(*p);
        }
      }
      pending.push_back(match);
      if (static_cast<int>(consistent.size()) >= lc.min_join_matches) {
        Join(k, consistent);
        return true;
      }
    }
  }
  return changed;
}

bool Mapper::Impl::AcceptAcrossRobots(int i, int k, const Pose2& T_i_k,
                                      std::vector<double>& distance) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const auto add_edge = [&](const PendingJoin& m) {
    EdgeRecord edge;
    edge.from = m.i;
    edge.to = m.k;
    edge.T_from_to = m.T_i_k;
    edge.information = Information(lc.sigma_xy, lc.sigma_theta);
    edge.loop = true;
    edge.closure = static_cast<int>(closures.size());
    closures.push_back({m.i, m.k, m.T_i_k, "accepted", true});
    AddEdge(edge, options.graph.loop_uncertainty);
    ++stats.accepted;
  };
  if (distance.empty()) {
    distance = uncertainty.DistancesFrom(k);
  }
  const Pose2 error = Between(Between(At(nodes, i).estimate, At(nodes, k).estimate), T_i_k);
  const double u =
      std::min(distance[static_cast<std::size_t>(i)], lc.appearance_gate_max_uncertainty);
  if (error.translation().norm() <= lc.gate_xy + lc.gate_xy_per_m * u &&
      std::abs(error.theta()) <= lc.gate_theta + lc.gate_theta_per_m * u) {
    add_edge({i, k, T_i_k});
    return error.translation().norm() > options.graph.online_trigger_xy ||
           std::abs(error.theta()) > options.graph.online_trigger_theta;
  }
  const double max_correction =
      std::max(lc.max_correction, lc.max_drift * distance[static_cast<std::size_t>(i)]);
  if (error.translation().norm() > max_correction ||
      std::abs(error.theta()) > lc.max_correction_theta) {
    GRIDSLAM_LOG_DEBUG("appearance match {}-{} rejected: moves the map {:.2f} m {:.3f} rad", i, k,
                       error.translation().norm(), error.theta());
    return false;
  }
  // The estimate disagrees: accept only with independent matches between the same two robots
  // that agree with this one (then the estimate was wrong; DESIGN.md 1.6 pairwise consistency).
  const PendingJoin match{i, k, T_i_k};
  const auto robot_of = [&](int id) { return At(nodes, id).robot; };
  std::vector<std::size_t> support;
  for (std::size_t s = 0; s < across.size(); ++s) {
    const std::optional<PendingJoin> p = Oriented(across[s], robot_of(i), robot_of(k), robot_of);
    if (p.has_value() && Independent(match, *p, nodes, lc.independent_travel) &&
        PairConsistent(match, *p, nodes, lc)) {
      support.push_back(s);
    }
  }
  const int needed = std::max(lc.min_join_matches + 1, lc.min_consistent_gated);
  if (static_cast<int>(support.size()) + 1 < needed) {
    GRIDSLAM_LOG_DEBUG("appearance match {}-{} off by {:.2f} m {:.3f} rad: {} agree, waits", i, k,
                       error.translation().norm(), error.theta(), support.size());
    across.push_back(match);
    return false;
  }
  GRIDSLAM_LOG_DEBUG("{} consistent matches between robots {} and {} correct the map by {:.2f} m",
                     support.size() + 1, robot_of(i), robot_of(k), error.translation().norm());
  add_edge(match);
  for (auto it = support.rbegin(); it != support.rend(); ++it) {
    add_edge(across[*it]);
    across.erase(across.begin() + static_cast<std::ptrdiff_t>(*it));
  }
  OptimizeNow();  // a correction of metres: more than a few online SGD iterations can absorb
  return false;
}

void Mapper::Impl::OptimizeNow() {
  const auto start = std::chrono::steady_clock::now();
  RebuildOptimizer();
  pose_graph::PoseGraph graph = sgd->graph();
  pose_graph::Optimize(graph, options.optimizer);
  for (Node& node : nodes) {
    node.estimate = graph.vertex(graph.IndexOf(node.id)).T_map_v;
  }
  RebuildOptimizer();
  stats.seconds_optimization += SecondsSince(start);
}

void Mapper::Impl::Join(int k, const std::vector<PendingJoin>& matches) {
  const PendingJoin& anchor = matches.front();
  const int robot_a = At(nodes, anchor.i).robot;
  const int robot_b = At(nodes, anchor.k).robot;
  const int component_a = FindComponent(robot_a);
  const int component_b = FindComponent(robot_b);
  std::vector<bool> moved(robots.size(), false);
  for (std::size_t r = 0; r < robots.size(); ++r) {
    moved[r] = FindComponent(static_cast<int>(r)) == component_b;
  }
  // Move component b into a's frame so that anchor.k lands at X_i * T_i_k.
  const Pose2 T_a_b =
      At(nodes, anchor.i).estimate * anchor.T_i_k * At(nodes, anchor.k).estimate.Inverse();
  for (Node& node : nodes) {
    if (moved[static_cast<std::size_t>(node.robot)]) {
      node.estimate = T_a_b * node.estimate;
    }
  }
  robot_parent[static_cast<std::size_t>(component_b)] = component_a;
  for (const PendingJoin& m : matches) {
    GRIDSLAM_LOG_DEBUG(
        "join match {} (robot {}, t {:.1f}, travel {:.1f} m) - {} (robot {}, t {:.1f}, "
        "travel {:.1f} m)",
        m.i, At(nodes, m.i).robot, ToSeconds(At(nodes, m.i).time), At(nodes, m.i).travel, m.k,
        At(nodes, m.k).robot, ToSeconds(At(nodes, m.k).time), At(nodes, m.k).travel);
    EdgeRecord edge;
    edge.from = m.i;
    edge.to = m.k;
    edge.T_from_to = m.T_i_k;
    edge.information = Information(options.loop_closure.sigma_xy, options.loop_closure.sigma_theta);
    edge.loop = true;
    edge.closure = static_cast<int>(closures.size());
    closures.push_back({m.i, m.k, m.T_i_k, "joined", true});
    edges.push_back(edge);
    uncertainty.AddEdge(m.i, m.k, options.graph.loop_uncertainty);
    ++stats.accepted;
  }
  // Joined components: drop pending matches that are now inside one component.
  pending.erase(std::remove_if(pending.begin(), pending.end(),
                               [&](const PendingJoin& p) {
                                 return FindComponent(At(nodes, p.i).robot) ==
                                        FindComponent(At(nodes, p.k).robot);
                               }),
                pending.end());
  joins.push_back({robot_a, robot_b, now, anchor.i, anchor.k, static_cast<int>(matches.size())});
  ++stats.joins;
  (void)k;
  CatchUp(moved, matches);
}

void Mapper::Impl::CatchUp(const std::vector<bool>& moved, std::vector<PendingJoin> trusted) {
  const loop_closure::LoopClosureOptions& lc = options.loop_closure;
  const auto start = std::chrono::steady_clock::now();
  OptimizeNow();
  const auto is_b = [&](const Node& n) { return moved[static_cast<std::size_t>(n.robot)]; };
  std::vector<bool> linked(nodes.size(), false);
  for (const PendingJoin& t : trusted) {
    linked[static_cast<std::size_t>(t.k)] = true;
  }
  long aligned = 0;
  int added_total = 0;
  for (int round = 0; round < lc.catch_up_rounds; ++round) {
    // Every key map of b not yet linked: the nearest key maps of a under the joined estimate.
    std::vector<PendingJoin> found;
    for (const Node& b : nodes) {
      if (!is_b(b) || !b.alignable || linked[static_cast<std::size_t>(b.id)]) {
        continue;
      }
      std::vector<std::pair<double, int>> candidates;
      for (const Node& a : nodes) {
        const double d = (a.estimate.translation() - b.estimate.translation()).norm();
        if (!is_b(a) && a.alignable && d < lc.max_search_radius) {
          candidates.emplace_back(d, a.id);
        }
      }
      std::sort(candidates.begin(), candidates.end());
      std::vector<int> chosen;
      for (const auto& candidate : candidates) {
        // Not a structured binding: clang 14 cannot capture one in the lambda below.
        const int id = candidate.second;
        if (static_cast<int>(chosen.size()) >= lc.max_candidates) {
          break;
        }
        if (std::none_of(chosen.begin(), chosen.end(), [&](int other) {
              return At(nodes, other).robot == At(nodes, id).robot &&
                     std::abs(At(nodes, other).travel - At(nodes, id).travel) <
                         lc.candidate_spacing;
            })) {
          chosen.push_back(id);
        }
      }
      for (const int i : chosen) {
        ++stats.candidates;
        ++aligned;
        if (const std::optional<Pose2> measured = TryAlign(i, b.id, nullptr)) {
          found.push_back({i, b.id, *measured});
        }
      }
    }
    // Kept: the matches that min_join_matches others (found or trusted) agree with.
    std::vector<PendingJoin> pool = trusted;
    pool.insert(pool.end(), found.begin(), found.end());
    std::vector<PendingJoin> accepted;
    for (const PendingJoin& f : found) {
      const auto support = std::count_if(pool.begin(), pool.end(), [&](const PendingJoin& p) {
        return Independent(f, p, nodes, lc.independent_travel) && PairConsistent(f, p, nodes, lc);
      });
      if (support < lc.min_join_matches) {
        continue;
      }
      EdgeRecord edge;
      edge.from = f.i;
      edge.to = f.k;
      edge.T_from_to = f.T_i_k;
      edge.information = Information(lc.sigma_xy, lc.sigma_theta);
      edge.loop = true;
      edge.closure = static_cast<int>(closures.size());
      closures.push_back({f.i, f.k, f.T_i_k, "accepted", false});
      AddEdge(edge, options.graph.loop_uncertainty);
      ++stats.accepted;
      linked[static_cast<std::size_t>(f.k)] = true;
      accepted.push_back(f);
    }
    added_total += static_cast<int>(accepted.size());
    trusted.insert(trusted.end(), accepted.begin(), accepted.end());
    if (accepted.empty()) {
      break;
    }
    OptimizeNow();
  }
  GRIDSLAM_LOG_DEBUG("join catch-up: {} alignments, {} loop edges, {:.2f} s", aligned, added_total,
                     SecondsSince(start));
}

}  // namespace gridslam::pipeline
