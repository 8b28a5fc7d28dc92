#include "gridslam/loop_closure/closure_arbiter.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "gridslam/common/logging.hpp"

namespace gridslam::loop_closure {
namespace {

// `v` without its component along the unit `axis`.
Eigen::Vector2d WithoutAxis(const Eigen::Vector2d& v, const Eigen::Vector2d& axis) {
  return v - v.dot(axis) * axis;
}

// Two free axes this close to parallel (|sin| of the angle between them) count as one.
constexpr double kParallelAxes = 0.17;  // 10 degrees

bool Within(const Pose2& loop, double xy, double theta) {
  return loop.translation().norm() < xy && std::abs(loop.theta()) < theta;
}

}  // namespace

std::string_view ToString(ClosureOutcome outcome) {
  switch (outcome) {
    case ClosureOutcome::kAccepted:
      return "accepted";
    case ClosureOutcome::kGated:
      return "gate";
    case ClosureOutcome::kPending:
      return "pending";
    case ClosureOutcome::kJoined:
      return "joined";
    case ClosureOutcome::kPruned:
      return "pruned";
  }
  return "unknown";
}

Match Reversed(const Match& match) {
  Match reversed{match.k, match.i, match.T_i_k.Inverse()};
  reversed.wide_search = match.wide_search;
  if (match.free_axis.has_value()) {
    reversed.free_axis = match.T_i_k.Rotation().transpose() * *match.free_axis;
    reversed.free_sigma = match.free_sigma;
  }
  if (match.weak_axis.has_value()) {
    reversed.weak_axis = match.T_i_k.Rotation().transpose() * *match.weak_axis;
    reversed.weak_sigma = match.weak_sigma;
  }
  return reversed;
}

Pose2 ClosureError(const Match& match, const GraphView& graph) {
  const Pose2 predicted = Between(graph.Estimate(match.i), graph.Estimate(match.k));
  const Pose2 error = Between(predicted, match.T_i_k);
  if (!match.free_axis.has_value()) {
    return error;
  }
  // error's translation is R_predicted^T (t_measured - t_predicted), t in i's frame.
  const Eigen::Vector2d axis = predicted.Rotation().transpose() * *match.free_axis;
  const Eigen::Vector2d measured = WithoutAxis(error.translation(), axis);
  return Pose2(measured.x(), measured.y(), error.theta());
}

double DriftBound(double u, double theta, const LoopClosureOptions& options) {
  return options.max_drift * u + std::abs(theta) * 0.5 * u;
}

double HeadingDriftBound(double u, const LoopClosureOptions& options) {
  return std::max(options.max_correction_theta, options.max_drift_theta * u);
}

bool BeyondDrift(const Pose2& error, double u, const LoopClosureOptions& options) {
  const double max_translation =
      std::max(options.max_correction, DriftBound(u, error.theta(), options));
  return error.translation().norm() > max_translation ||
         std::abs(error.theta()) > HeadingDriftBound(u, options);
}

bool InGate(const Pose2& error, double u, const LoopClosureOptions& options) {
  return error.translation().norm() <= options.gate_xy + options.gate_xy_per_m * u &&
         std::abs(error.theta()) <= options.gate_theta + options.gate_theta_per_m * u;
}

Pose2 LoopError(const Match& a, const Match& b, const GraphView& graph) {
  const Pose2 T_bi_ai = Between(graph.Estimate(b.i), graph.Estimate(a.i));
  const Pose2 loop =
      a.T_i_k * Between(graph.Estimate(a.k), graph.Estimate(b.k)) * b.T_i_k.Inverse() * T_bi_ai;
  if (!a.free_axis.has_value() && !b.free_axis.has_value()) {
    return loop;
  }
  // The loop starts and ends in a.i's frame: a translation error of a (in a.i's frame) moves its
  // translation as it is, one of b (in b.i's frame) rotated into a.i's frame.
  std::vector<Eigen::Vector2d> axes;
  if (a.free_axis.has_value()) {
    axes.push_back(*a.free_axis);
  }
  if (b.free_axis.has_value()) {
    axes.push_back(T_bi_ai.Rotation().transpose() * *b.free_axis);
  }
  Eigen::Vector2d measured = WithoutAxis(loop.translation(), axes.front());
  if (axes.size() == 2) {
    const double sine = axes[0].x() * axes[1].y() - axes[0].y() * axes[1].x();
    if (std::abs(sine) > kParallelAxes) {
      measured.setZero();  // two crossing free axes leave no translation measured
    }
  }
  return Pose2(measured.x(), measured.y(), loop.theta());
}

bool PairConsistent(const Match& a, const Match& b, const GraphView& graph,
                    const LoopClosureOptions& options) {
  const Pose2 loop = LoopError(a, b, graph);
  const double span =
      std::max((graph.Estimate(a.k).translation() - graph.Estimate(b.k).translation()).norm(),
               (graph.Estimate(a.i).translation() - graph.Estimate(b.i).translation()).norm());
  return Within(loop, options.pairwise_xy + options.gate_xy_per_m * span,
                options.pairwise_theta + options.gate_theta_per_m * span);
}

bool Independent(const Match& a, const Match& b, const GraphView& graph, double travel) {
  return std::abs(graph.Travel(a.i) - graph.Travel(b.i)) >= travel &&
         std::abs(graph.Travel(a.k) - graph.Travel(b.k)) >= travel;
}

int Support(const Match& match, const std::vector<Match>& pool, const GraphView& graph,
            const LoopClosureOptions& options) {
  return static_cast<int>(std::count_if(pool.begin(), pool.end(), [&](const Match& p) {
    return Independent(match, p, graph, options.independent_travel) &&
           PairConsistent(match, p, graph, options);
  }));
}

bool ClosureArbiter::IndependentEnough(const std::vector<Match>& group,
                                       const GraphView& graph) const {
  // A wide window may hold a look-alike of the place (a row of identical bays, a road between
  // trees), and the key maps along the revisit see it alike: their matches agree whether it is
  // the place or not. Two matches far apart along both paths see two places.
  if (std::none_of(group.begin(), group.end(), [](const Match& m) { return m.wide_search; })) {
    return true;
  }
  for (std::size_t a = 0; a < group.size(); ++a) {
    for (std::size_t b = a + 1; b < group.size(); ++b) {
      if (Independent(group[a], group[b], graph, options_.independent_travel)) {
        return true;
      }
    }
  }
  return false;
}

Decision ClosureArbiter::OfferPrior(const Match& match, double u, bool from_search,
                                    const GraphView& graph) {
  Decision decision;
  decision.error = ClosureError(match, graph);
  // A closure found by the prior search is never trusted alone: in a wide window a look-alike
  // place (a row of identical bays) may score best; it needs the support of other closures.
  decision.in_gate = !from_search && InGate(decision.error, u, options_);
  decision.accepted = {match};
  if (decision.in_gate) {
    decision.verdict = Verdict::kAccept;
    return decision;
  }
  if (BeyondDrift(decision.error, u, options_)) {
    decision.verdict = Verdict::kReject;
    decision.accepted.clear();
    return decision;
  }
  // Outside the gate: once enough recent gated closures agree with each other (the loops they
  // form with the graph close), the estimate is what was wrong, and they are accepted together
  // (docs/design.md §1.6: pairwise consistency of several closures).
  // Matches of one key map are one piece of evidence (its scans): each counts once.
  const auto consistent = [&](const Match& a, const Match& b) {
    return Within(LoopError(a, b, graph), options_.pairwise_xy, options_.pairwise_theta);
  };
  std::vector<int> evidence = {match.k};
  for (const Match& g : gated_) {
    if (g.k != match.k && match.k - g.k <= options_.gated_window && consistent(match, g)) {
      decision.accepted.push_back(g);
      if (std::find(evidence.begin(), evidence.end(), g.k) == evidence.end()) {
        evidence.push_back(g.k);
      }
    }
  }
  const std::vector<Match>& group = decision.accepted;
  // Every two members must agree, not only each with the new match: a ridge (its position along
  // a corridor unmeasured) agrees with closures anywhere along it, which may be a place and its
  // look-alike. Evidence for two places is no evidence: the group waits.
  bool mutual = true;
  for (std::size_t a = 1; a < group.size() && mutual; ++a) {
    for (std::size_t b = a + 1; b < group.size() && mutual; ++b) {
      mutual = consistent(group[a], group[b]);
    }
  }
  if (static_cast<int>(evidence.size()) < options_.min_consistent_gated || !mutual ||
      !IndependentEnough(group, graph)) {
    decision.verdict = Verdict::kWait;
    decision.accepted.resize(1);
    gated_.push_back(match);
    return decision;
  }
  decision.verdict = Verdict::kAcceptGroup;
  gated_.erase(std::remove_if(gated_.begin(), gated_.end(),
                              [&](const Match& g) {
                                return std::any_of(group.begin(), group.end(), [&](const Match& m) {
                                  return m.i == g.i && m.k == g.k;
                                });
                              }),
               gated_.end());
  return decision;
}

Decision ClosureArbiter::OfferWithinMap(const Match& match, double u, const GraphView& graph) {
  Decision decision;
  decision.error = ClosureError(match, graph);
  decision.in_gate =
      InGate(decision.error, std::min(u, options_.appearance_gate_max_uncertainty), options_);
  decision.accepted = {match};
  if (decision.in_gate) {
    decision.verdict = Verdict::kAccept;
    return decision;
  }
  if (BeyondDrift(decision.error, u, options_)) {
    decision.verdict = Verdict::kReject;
    decision.accepted.clear();
    return decision;
  }
  // The estimate disagrees: accept only with independent matches between the same two robots
  // that agree with this one (then the estimate was wrong; docs/design.md §1.6 pairwise
  // consistency).
  const auto robot_of = [&](int id) { return graph.Robot(id); };
  std::vector<std::size_t> support;
  for (std::size_t s = 0; s < within_map_.size(); ++s) {
    const std::optional<Match> p =
        Oriented(within_map_[s], graph.Robot(match.i), graph.Robot(match.k), robot_of);
    if (p.has_value() && Independent(match, *p, graph, options_.independent_travel) &&
        PairConsistent(match, *p, graph, options_)) {
      support.push_back(s);
    }
  }
  const int needed = std::max(options_.min_join_matches + 1, options_.min_consistent_gated);
  if (static_cast<int>(support.size()) + 1 < needed) {
    decision.verdict = Verdict::kWait;
    within_map_.push_back(match);
    return decision;
  }
  decision.verdict = Verdict::kAcceptGroup;
  for (auto it = support.rbegin(); it != support.rend(); ++it) {
    decision.accepted.push_back(within_map_[*it]);
    within_map_.erase(within_map_.begin() + static_cast<std::ptrdiff_t>(*it));
  }
  return decision;
}

Decision ClosureArbiter::OfferJoin(const Match& match, const GraphView& graph) {
  Decision decision;
  decision.accepted = {match};
  const int other = graph.Component(match.i);
  const int component = graph.Component(match.k);
  const auto component_of = [&](int id) { return graph.Component(id); };
  for (const Match& stored : joinable_) {
    // A match found from the other side (the other robot's query) counts reversed.
    const std::optional<Match> p = Oriented(stored, other, component, component_of);
    if (p.has_value() && Independent(match, *p, graph, options_.independent_travel) &&
        PairConsistent(match, *p, graph, options_)) {
      decision.accepted.push_back(*p);
    }
  }
  joinable_.push_back(match);
  decision.verdict = static_cast<int>(decision.accepted.size()) >= options_.min_join_matches
                         ? Verdict::kAcceptGroup
                         : Verdict::kWait;
  if (decision.verdict == Verdict::kWait) {
    decision.accepted.resize(1);
  }
  return decision;
}

void ClosureArbiter::ForgetWithinComponents(const GraphView& graph) {
  joinable_.erase(
      std::remove_if(joinable_.begin(), joinable_.end(),
                     [&](const Match& p) { return graph.Component(p.i) == graph.Component(p.k); }),
      joinable_.end());
}

}  // namespace gridslam::loop_closure
