// Options of the loop-closure search and its gates (docs/design.md §1.6; docs/method.md §1.5.6).
#pragma once

#include "gridslam/common/options.hpp"
#include "gridslam/loop_closure/free_space_check.hpp"
#include "gridslam/loop_closure/grid_refinement.hpp"
#include "gridslam/loop_closure/prior_search.hpp"

namespace gridslam::loop_closure {

struct LoopClosureOptions {
  bool enabled = true;
  /// Key maps closer than this along the robot's own path are never candidates (the paper skips
  /// the 12 most recent key maps) [m].
  double min_travel_gap = 10.0;
  /// Candidates: older key maps whose predicted centre lies within this radius ... [m]
  double search_radius = 4.0;
  /// ... plus this much per metre of uncertainty distance (graph path length) [m/m].
  double search_radius_per_m = 0.05;
  /// ... capped here [m].
  double max_search_radius = 12.0;
  /// Aligned candidates per new key map at most (the nearest, spread along the path) [-].
  int max_candidates = 3;
  /// Candidates closer than this to another chosen candidate along the path are skipped [m].
  double candidate_spacing = 3.0;
  /// Consistency gate with the current estimate: a closure is accepted when it differs from the
  /// predicted relative pose by at most gate_xy + gate_xy_per_m * u [m] and
  /// gate_theta + gate_theta_per_m * u [rad], u the uncertainty distance between the key maps.
  double gate_xy = 0.3;
  double gate_xy_per_m = 0.04;
  double gate_theta = 0.05;
  double gate_theta_per_m = 0.004;
  /// Closures outside the gate are accepted when this many (including the new one), from key
  /// maps at most gated_window key maps apart, are mutually consistent [-].
  int min_consistent_gated = 3;
  int gated_window = 30;
  /// Loop edges: standard deviations of the measured relative pose [m, rad].
  double sigma_xy = 0.03;
  double sigma_theta = 0.005;
  /// Closures between components (robots not yet joined) need this many mutually consistent
  /// verified matches before the components are joined [-].
  int min_join_matches = 2;
  /// Two closures are mutually consistent when the loop they form with the graph closes within
  /// this [m] and [rad].
  double pairwise_xy = 0.3;
  double pairwise_theta = 0.05;
  /// Global appearance search across components: run it for every n-th new key map [-].
  int appearance_every = 2;
  /// Key maps voted for by the appearance search that are aligned [-].
  int appearance_candidates = 3;
  /// Key maps enter a robot's appearance index at least this far apart along its path (key maps
  /// overlap by most of their area; near-duplicates would crowd out the vote) [m].
  double appearance_spacing = 3.0;
  /// Appearance matches (no prior) count as independent evidence of each other when their key
  /// maps lie at least this far apart along both paths: an aliased place matches a run of
  /// neighbouring key maps, all consistently. Key maps 2 m apart still share about 85 % of a
  /// 15 m window, so their matches repeat one piece of evidence: at 2 m two key maps 4 m apart
  /// joined two simulated robots rotated by 180 degrees (office, 3 robots, seed 2); 5 m (a third
  /// of the window) refuses that join and changes the split real-log runs' errors by < 2 mm
  /// (docs/multi_robot.md; 8 m delays joins and was worse) [m].
  double independent_travel = 5.0;
  /// An appearance match within one map that disagrees with the estimate is refused as aliasing
  /// when it would move the map by more than max(max_correction, max_drift * u + |theta| * u / 2)
  /// [m], [-], u the uncertainty distance between the key maps and theta the match's rotation
  /// correction (the displacement that heading error causes, closure_arbiter.hpp DriftBound), or
  /// turn it by more than max(max_correction_theta, max_drift_theta * u) [rad], [rad/m]
  /// (closure_arbiter.hpp HeadingDriftBound): a path gathers heading error with its length, as
  /// it gathers translation error. A look-alike turned by 90 or 180 degrees in a building whose
  /// loops are short is refused; a long excursion may come back turned by more than 0.5 rad.
  double max_correction = 10.0;
  double max_drift = 0.05;
  double max_correction_theta = 0.5;
  double max_drift_theta = 0.004;
  /// The gate of appearance matches grows with the uncertainty distance only up to this: unlike
  /// prior-based candidates they were not preselected by proximity [m].
  double appearance_gate_max_uncertainty = 10.0;
  /// Rounds of the catch-up search after two robots' graphs are joined [-].
  int catch_up_rounds = 2;
  /// A lone verified match between two components (no independent second one) is verified by
  /// aligning the newer robot's key maps within this path distance of it under the relative
  /// frame it implies (pipeline/join_verifier.hpp); 0 = never [m]. It joins the robots of a
  /// building they cross only once (fr-clinic in 3 robots). In a symmetric building (the
  /// simulated office) a rotated look-alike verifies as well as the truth; the free-space check
  /// (free_space_check) refuses it (docs/multi_robot.md, "Round 16").
  double join_verification_travel = 20.0;
  /// The same verification inside one map: an appearance match that disagrees with the estimate
  /// (a loop whose drift outgrew the prior search) and has no independent support waits; it is
  /// verified at once by aligning the key maps within this path distance of its newer key map,
  /// under the correction it implies, with the key maps it predicts them beside (at least
  /// min_travel_gap behind them along the path). Once per key map; 0 = never [m].
  double loop_verification_travel = 20.0;
  /// After the final optimization, loop edges whose chi2 exceeds this are removed [-].
  double prune_chi2 = 25.0;
  /// When feature alignment of a prior-based candidate fails and the uncertainty distance is
  /// below prior_max_uncertainty [m], refine the predicted transform on the distance field and
  /// accept it if at least prior_min_inliers of the points agree [-], the weaker translation
  /// direction keeps prior_min_constraint of the stronger's information [-] (no corridor
  /// sliding), and the grids verify. When the uncertainty distance allows a prediction error
  /// beyond the refinement's basin, a correlative search around the prediction seeds it
  /// (prior_search.hpp).
  bool prior_refinement = true;
  double prior_max_uncertainty = 1000.0;
  double prior_min_inliers = 0.6;
  double prior_min_constraint = 0.1;
  RefinementOptions refinement;
  PriorSearchOptions prior_search;
  /// A join (of either kind) whose alignments contradict free space beyond the robots' own
  /// contradiction is refused (free_space_check.hpp).
  FreeSpaceCheckOptions free_space_check;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled, "Search for loop closures");
    v("min_travel_gap", min_travel_gap,
      "Minimum path distance between a key map and a candidate [m]");
    v("search_radius", search_radius, "Candidate search radius around the predicted pose [m]");
    v("search_radius_per_m", search_radius_per_m,
      "Search radius growth per metre of uncertainty distance [m/m]");
    v("max_search_radius", max_search_radius, "Search radius cap [m]");
    v("max_candidates", max_candidates, "Candidates aligned per key map at most [-]");
    v("candidate_spacing", candidate_spacing, "Minimum path spacing of chosen candidates [m]");
    v("gate_xy", gate_xy, "Consistency gate: translation tolerance [m] ...");
    v("gate_xy_per_m", gate_xy_per_m, "... plus this per metre of uncertainty distance [m/m]");
    v("gate_theta", gate_theta, "Consistency gate: rotation tolerance [rad] ...");
    v("gate_theta_per_m", gate_theta_per_m, "... plus this per metre [rad/m]");
    v("min_consistent_gated", min_consistent_gated,
      "Mutually consistent gated closures that are accepted together [-]");
    v("gated_window", gated_window, "... from key maps at most this many apart [-]");
    v("sigma_xy", sigma_xy, "Loop edge standard deviation, translation [m]");
    v("sigma_theta", sigma_theta, "Loop edge standard deviation, rotation [rad]");
    v("min_join_matches", min_join_matches,
      "Mutually consistent matches needed to join two robots' graphs [-]");
    v("pairwise_xy", pairwise_xy, "Pairwise consistency tolerance, translation [m]");
    v("pairwise_theta", pairwise_theta, "Pairwise consistency tolerance, rotation [rad]");
    v("appearance_every", appearance_every,
      "Run the global appearance search for every n-th key map (0 = never) [-]");
    v("appearance_candidates", appearance_candidates, "Best-voted key maps aligned [-]");
    v("appearance_spacing", appearance_spacing,
      "Path distance between key maps put into a robot's appearance index [m]");
    v("independent_travel", independent_travel,
      "Appearance matches are independent evidence when this far apart along both paths [m]");
    v("max_correction", max_correction,
      "Appearance matches moving the map more than max(this, max_drift * u + |rotation| * u / 2), "
      "u the uncertainty distance, are refused [m]");
    v("max_drift", max_drift, "... drift per metre of uncertainty distance [-]");
    v("max_correction_theta", max_correction_theta,
      "Appearance matches turning the map more than max(this, max_drift_theta * u) are "
      "refused [rad]");
    v("max_drift_theta", max_drift_theta,
      "... heading drift per metre of uncertainty distance [rad/m]");
    v("appearance_gate_max_uncertainty", appearance_gate_max_uncertainty,
      "Cap of the uncertainty distance in the gate of appearance matches [m]");
    v("catch_up_rounds", catch_up_rounds, "Rounds of the catch-up search after a join [-]");
    v("join_verification_travel", join_verification_travel,
      "A lone match between two robots is verified by aligning the newer robot's key maps "
      "within this path distance of it under the frame it implies; 0 = never [m]");
    v("loop_verification_travel", loop_verification_travel,
      "A waiting appearance match within one map is verified by aligning the key maps within "
      "this path distance of it under the correction it implies; 0 = never [m]");
    v("prune_chi2", prune_chi2, "Loop edges above this chi2 after optimization are removed [-]");
    v("prior_refinement", prior_refinement,
      "Fall back to refining the predicted transform when feature alignment fails");
    v("prior_max_uncertainty", prior_max_uncertainty,
      "... only below this uncertainty distance [m]");
    v("prior_min_inliers", prior_min_inliers, "... accepting at least this inlier fraction [-]");
    v("prior_min_constraint", prior_min_constraint,
      "... and this ratio of weakest to strongest translation information [-]");
    v.Section("refinement", refinement, "Refinement of alignments on the distance field");
    v.Section("prior_search", prior_search,
              "Correlative search around the prediction seeding the prior refinement");
    v.Section("free_space_check", free_space_check,
              "Joins checked against the free space each robot observed");
  }
  [[nodiscard]] Status Validate() const;
};

}  // namespace gridslam::loop_closure
