// Options of the optimizer's defence against wrong loop closures (robust_optimization.md). The
// mechanism down-weights loop-closure edges (IsLoopClosure, pose_graph.hpp; the odometry chain is
// trusted) whose error does not fit the rest of the graph:
//  - "dcs": dynamic covariance scaling (Agarwal et al. 2013), the closed form of switchable
//    constraints (Sünderhauf & Protzel 2012): each loop edge's information is scaled by
//    min(1, 2 Phi / (Phi + chi^2))^2 at every Gauss-Newton linearization; run for several Phi
//    from the same start, keeping the result of the lowest truncated cost;
//  - "gnc": graduated non-convexity (Yang et al. 2020) with the Geman-McClure kernel: the kernel
//    scale starts wide enough that the cost is convex in the residuals, and shrinks by
//    `gnc_factor` per step (a few Gauss-Newton iterations each) down to `gnc_threshold`.
// Both end with a polish: Gauss-Newton on the truncated cost (loop edges with chi^2 above
// `inlier_chi2` are left out, the others count in full), so a clean graph ends at its plain
// least-squares optimum chi*.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/options.hpp"

namespace gridslam::pose_graph {

struct RobustOptions {
  /// "none", "dcs" or "gnc" (see above).
  std::string mechanism = "none";
  /// DCS: the values of Phi tried, each from the same start; the result with the lowest truncated
  /// cost (sum of min(chi^2, inlier_chi2) over loop edges plus chi^2 of the others) is kept
  /// [chi^2 of an edge]. Agarwal et al. use 1; 1 keeps wrong closures out of intel, 100 keeps
  /// manhattan's correct closures in from its drifted odometry guess (robust_optimization.md).
  std::vector<double> dcs_phi = {1.0, 10.0, 100.0};
  /// GNC: final Geman-McClure scale c^2 [chi^2 of an edge].
  double gnc_threshold = 9.0;
  /// GNC: the scale is divided by this per step (Yang et al.: 1.4).
  double gnc_factor = 1.4;
  /// GNC: Gauss-Newton iterations per step.
  int gnc_step_iterations = 3;
  /// Polish: loop edges above this chi^2 are dropped from the final Gauss-Newton (0: no polish);
  /// also the gate of the truncated cost that picks among DCS runs [chi^2 of an edge]. The largest
  /// loop-edge chi^2 at the optimum of the shared graphs is 13.2 (manhattan). 16 (about the
  /// 99.9 % quantile of chi^2 with 3 dof) also beats intel's 100 local and grouped outliers, but
  /// with initialization chordal it leaves clean manhattan at 1.0055 chi* (one correct closure
  /// dropped); 25 keeps every clean graph at chi* (robust_optimization.md).
  double inlier_chi2 = 25.0;

  template <class V>
  void Visit(V& v) {
    v("mechanism", mechanism,
      "Wrong-loop-closure defence: none, dcs (dynamic covariance scaling) or gnc (graduated "
      "non-convexity, Geman-McClure)");
    v("dcs_phi", dcs_phi, "DCS Phi values tried; the lowest truncated cost wins [chi^2]");
    v("gnc_threshold", gnc_threshold, "GNC final Geman-McClure scale [chi^2]");
    v("gnc_factor", gnc_factor, "GNC scale divisor per step");
    v("gnc_step_iterations", gnc_step_iterations, "Gauss-Newton iterations per GNC step");
    v("inlier_chi2", inlier_chi2,
      "Polish: loop edges above this chi^2 are dropped from the final Gauss-Newton (0: none) "
      "[chi^2]");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(mechanism == "none" || mechanism == "dcs" || mechanism == "gnc",
                "optimizer.robust.mechanism is none, dcs or gnc"));
    GRIDSLAM_RETURN_IF_ERROR(Require(!dcs_phi.empty(), "optimizer.robust.dcs_phi not empty"));
    for (const double phi : dcs_phi) {
      GRIDSLAM_RETURN_IF_ERROR(Require(phi > 0.0, "optimizer.robust.dcs_phi > 0"));
    }
    GRIDSLAM_RETURN_IF_ERROR(Require(gnc_threshold > 0.0, "optimizer.robust.gnc_threshold > 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(gnc_factor > 1.0, "optimizer.robust.gnc_factor > 1"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(gnc_step_iterations >= 1, "optimizer.robust.gnc_step_iterations >= 1"));
    return Require(inlier_chi2 >= 0.0, "optimizer.robust.inlier_chi2 >= 0");
  }
};

}  // namespace gridslam::pose_graph
