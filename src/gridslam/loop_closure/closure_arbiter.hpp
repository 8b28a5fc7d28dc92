// The closure arbiter (docs/design.md §1.6): decides what becomes of a verified alignment between
// two key maps, given the current estimate of the graph. It owns no graph; it reads one through
// GraphView and answers with a Decision (the matches to turn into loop edges, if any). It holds
// the three queues of closures that wait for support, each an explicit state:
//   - gated: prior-based closures outside the consistency gate. Once min_consistent_gated
//     recent ones of as many distinct new key maps form mutually consistent loops with the
//     graph, the estimate was what was wrong, and they are accepted together;
//   - within_map: appearance matches inside one map component that disagree with the estimate
//     (but not by more than DriftBound allows, max_correction at least); accepted with enough
//     independent, consistent matches between the same two robots;
//   - joinable: matches between two map components not joined yet; min_join_matches
//     independent, consistent ones join the components (the caller joins them, then calls
//     ForgetWithinComponents).
// Contract: the arbiter never changes the graph; the caller adds the accepted matches (in the
// order given, first the new match) as loop edges. Deterministic: equal inputs, equal answers.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/loop_closure/loop_closure_options.hpp"

namespace gridslam::loop_closure {

/// What became of a closure (ClosureRecord::outcome). ToString gives the report's strings.
enum class ClosureOutcome {
  kAccepted,  ///< A loop edge of the graph.
  kGated,     ///< Outside the gate, waiting for a consistent group ("gate").
  kPending,   ///< Between components not joined yet ("pending").
  kJoined,    ///< One of the matches that joined two components.
  kPruned,    ///< Was a loop edge, removed by the final optimization.
};
[[nodiscard]] std::string_view ToString(ClosureOutcome outcome);

/// A verified alignment: the pose of key map k in key map i's frame.
struct Match {
  int i = 0;
  int k = 0;
  Pose2 T_i_k;
  /// Set for a ridge (a corridor, a straight road): the direction (unit, in i's frame) along
  /// which T_i_k's translation is not measured. Every check below ignores that component.
  std::optional<Eigen::Vector2d> free_axis = std::nullopt;
  /// Standard deviation of the translation along free_axis [m]: the spread of the window the
  /// search covered (uniform over +-w: w / sqrt(3)). Positive when free_axis is set.
  double free_sigma = 0.0;
  /// Found by the prior search's second, wide window (prior_search.hpp wide_window_per_m): a
  /// group that holds it is accepted only with two independent matches in it.
  bool wide_search = false;
  /// Set when the refinement constrained one direction poorly (a corridor) and the search's
  /// distinct peak placed the translation along it: that direction (unit, in i's frame), known
  /// only to weak_sigma [m]. The checks treat it as measured; only the edge's information is
  /// lower along it.
  std::optional<Eigen::Vector2d> weak_axis = std::nullopt;
  double weak_sigma = 0.0;
};

/// The match seen from the other side: i's pose in k's frame (the free and weak axes rotated
/// with it; the wide_search flag kept).
[[nodiscard]] Match Reversed(const Match& match);
/// `stored` oriented from group `from` to group `to` (group = robot or component, given by
/// `group` of a vertex id), or nullopt if it links other groups.
template <class Group>
[[nodiscard]] std::optional<Match> Oriented(const Match& stored, int from, int to, Group group) {
  const int gi = group(stored.i);
  const int gk = group(stored.k);
  if (gi == from && gk == to) {
    return stored;
  }
  if (gi == to && gk == from) {
    return Reversed(stored);
  }
  return std::nullopt;
}

/// What the arbiter reads of the graph (implemented by pipeline::KeyMapGraph, or a test).
class GraphView {
 public:
  virtual ~GraphView() = default;
  [[nodiscard]] virtual Pose2 Estimate(int id) const = 0;  ///< T_map_key of vertex `id`.
  [[nodiscard]] virtual double Travel(int id) const = 0;   ///< Path length of its robot [m].
  [[nodiscard]] virtual int Robot(int id) const = 0;
  [[nodiscard]] virtual int Component(int id) const = 0;  ///< Map component of its robot.
};

/// The verdict on one match.
enum class Verdict {
  kAccept,       ///< Agrees with the estimate: `accepted` = {the match}.
  kAcceptGroup,  ///< Disagrees, but with the support of waiting matches: all in `accepted`.
  kWait,         ///< Queued until other matches support it.
  kReject,       ///< Refused (an appearance match that would move the map too far).
};

struct Decision {
  Verdict verdict = Verdict::kWait;
  /// The matches to add as loop edges, the new one first (or, for a join, to join with).
  std::vector<Match> accepted;
  Pose2 error;  ///< Measured relative to predicted pose (Between(predicted, measured)).
  bool in_gate = false;
};

/// Between(predicted, measured): how far the match is from the current estimate; for a ridge,
/// without the translation along its free axis.
[[nodiscard]] Pose2 ClosureError(const Match& match, const GraphView& graph);
/// The largest translation a match inside one map may correct as drift of the path between its
/// key maps, `u` [m] their uncertainty distance: max_drift * u of translation drift, plus what
/// the match's own rotation correction `theta` [rad] displaces. However that heading error
/// accrued along the path, it turned the rest of the path about points at most u / 2 from the
/// revisit (the path leaves the place and comes back), so by at most |theta| * u / 2 [m].
[[nodiscard]] double DriftBound(double u, double theta, const LoopClosureOptions& options);
/// The largest rotation a match inside one map may correct as heading drift of the path between
/// its key maps, `u` [m] their uncertainty distance: max(max_correction_theta,
/// max_drift_theta * u) [rad]. The floor keeps the rotated look-alikes of a building with short
/// loops out (a match that turns the map by 90 or 180 degrees); the bound grows with the path,
/// because heading error does.
[[nodiscard]] double HeadingDriftBound(double u, const LoopClosureOptions& options);
/// True when a closure `error` (ClosureError) is more than the path between its key maps can
/// have drifted, `u` their uncertainty distance [m]: a translation beyond max(max_correction,
/// DriftBound) or a rotation beyond HeadingDriftBound. Such a match is a look-alike (a corridor
/// seen from the other end matches itself turned by pi), whichever search proposed it.
[[nodiscard]] bool BeyondDrift(const Pose2& error, double u, const LoopClosureOptions& options);
/// The consistency gate: `error` within gate_xy + gate_xy_per_m * u and gate_theta +
/// gate_theta_per_m * u, u the uncertainty distance between the key maps [m].
[[nodiscard]] bool InGate(const Pose2& error, double u, const LoopClosureOptions& options);
/// The loop a.i -> a.k (measured), a.k -> b.k (estimate), b.k -> b.i (measured), b.i -> a.i
/// (estimate): identity when both matches agree with each other and the estimate on each side.
/// For ridges, without the translation along their free axes (both removed when they cross:
/// then only the rotation is checked).
[[nodiscard]] Pose2 LoopError(const Match& a, const Match& b, const GraphView& graph);
/// Pairwise consistency of appearance matches: the loop closes within pairwise_xy/theta plus
/// the gate's growth per metre of the distance the loop spans on each side.
[[nodiscard]] bool PairConsistent(const Match& a, const Match& b, const GraphView& graph,
                                  const LoopClosureOptions& options);
/// Independent evidence: the key maps of `a` and `b` lie at least `travel` apart along both
/// paths (an aliased place matches a run of neighbouring key maps, all consistently).
[[nodiscard]] bool Independent(const Match& a, const Match& b, const GraphView& graph,
                               double travel);
/// How many of `pool` are independent of and pairwise consistent with `match`.
[[nodiscard]] int Support(const Match& match, const std::vector<Match>& pool,
                          const GraphView& graph, const LoopClosureOptions& options);

class ClosureArbiter {
 public:
  explicit ClosureArbiter(const LoopClosureOptions& options) : options_(options) {}

  /// A prior-based closure (the candidate was predicted by the estimate); `u` the uncertainty
  /// distance between its key maps; `from_search`: found by the correlative prior search, never
  /// trusted alone (outside the gate by definition); a group holding a match.wide_search needs
  /// two matches in it that are Independent (neighbouring key maps see one place, a look-alike
  /// as consistently as the truth). kAccept, kAcceptGroup (with gated closures
  /// of the last gated_window key maps, which leave the queue), kWait (queued as gated) or,
  /// outside the gate and BeyondDrift, kReject (not queued: a consistent group of look-alikes
  /// must not outvote the estimate).
  Decision OfferPrior(const Match& match, double u, bool from_search, const GraphView& graph);

  /// An appearance match inside one map component; `u` the uncertainty distance. kAccept (in
  /// the gate, u capped at appearance_gate_max_uncertainty), kReject (would move the map too
  /// far), kWait or kAcceptGroup (with queued matches between the same two robots).
  Decision OfferWithinMap(const Match& match, double u, const GraphView& graph);

  /// A match between two components not joined yet. kAcceptGroup when min_join_matches
  /// independent consistent matches (the new one first; matches found from the other side
  /// reversed) call for a join, else kWait. The match is queued in both cases.
  Decision OfferJoin(const Match& match, const GraphView& graph);
  /// After a join: drops the queued join matches that now lie inside one component.
  void ForgetWithinComponents(const GraphView& graph);

  [[nodiscard]] const std::vector<Match>& gated() const { return gated_; }
  [[nodiscard]] const std::vector<Match>& within_map() const { return within_map_; }
  [[nodiscard]] const std::vector<Match>& joinable() const { return joinable_; }
  [[nodiscard]] const LoopClosureOptions& options() const { return options_; }

 private:
  /// True unless `group` holds a wide-search match and no two of its matches are Independent.
  [[nodiscard]] bool IndependentEnough(const std::vector<Match>& group,
                                       const GraphView& graph) const;

  LoopClosureOptions options_;
  std::vector<Match> gated_;
  std::vector<Match> within_map_;
  std::vector<Match> joinable_;
};

}  // namespace gridslam::loop_closure
