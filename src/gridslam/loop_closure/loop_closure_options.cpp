#include "gridslam/loop_closure/loop_closure_options.hpp"

namespace gridslam::loop_closure {

Status LoopClosureOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(min_travel_gap >= 0.0, "loop_closure.min_travel_gap >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(search_radius > 0.0, "loop_closure.search_radius > 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(search_radius_per_m >= 0.0, "loop_closure.search_radius_per_m >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_search_radius >= search_radius,
                                   "loop_closure.max_search_radius >= search_radius"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_candidates >= 0, "loop_closure.max_candidates >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(gate_xy > 0.0 && gate_theta > 0.0, "loop_closure gates > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(sigma_xy > 0.0 && sigma_theta > 0.0, "loop_closure sigmas > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(min_join_matches >= 1, "loop_closure.min_join_matches >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(min_consistent_gated >= 2, "loop_closure.min_consistent_gated >= 2"));
  GRIDSLAM_RETURN_IF_ERROR(Require(gated_window >= 1, "loop_closure.gated_window >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(appearance_every >= 0, "loop_closure.appearance_every >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(appearance_candidates >= 0, "loop_closure.appearance_candidates >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(appearance_spacing >= 0.0, "loop_closure.appearance_spacing >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(independent_travel >= 0.0, "loop_closure.independent_travel >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(
      max_correction >= 0.0 && max_drift >= 0.0 && max_correction_theta >= 0.0 &&
          max_drift_theta >= 0.0,
      "loop_closure.max_correction, max_drift, max_correction_theta, max_drift_theta >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(appearance_gate_max_uncertainty >= 0.0,
                                   "loop_closure.appearance_gate_max_uncertainty >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(catch_up_rounds >= 0, "loop_closure.catch_up_rounds >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(join_verification_travel >= 0.0, "loop_closure.join_verification_travel >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(loop_verification_travel >= 0.0, "loop_closure.loop_verification_travel >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(prune_chi2 > 0.0, "loop_closure.prune_chi2 > 0"));
  GRIDSLAM_RETURN_IF_ERROR(prior_search.Validate());
  GRIDSLAM_RETURN_IF_ERROR(free_space_check.Validate());
  return refinement.Validate();
}

}  // namespace gridslam::loop_closure
