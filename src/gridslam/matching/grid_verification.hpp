// Verification of a key-map alignment by grid agreement (docs/design.md §1.5): feature inliers
// alone cannot tell a place from a look-alike (perceptual aliasing), the grids can. The obstacle
// points of map b are moved into map a by T_a_b; those landing in the part of a that a has observed
// form the overlap, and the fraction of them within `agreement_distance` of an obstacle of a (one
// lookup in a's distance field each) is the agreement. An obstacle of b that lands where a saw
// free space is evidence against the transform; one that lands in a's unknown area is no evidence.
// The fraction landing farther than `contradiction_distance` from any obstacle of a (deep in a's
// free space) is the contradiction: a look-alike shifted by a corridor period can agree on most
// walls (the periodic part) yet contradicts the grid wherever the look-alike differs, while noise
// and blur move points by a cell or two but rarely by more. With both directions given, a's
// points are checked against b as well; the worse direction decides.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/options.hpp"
#include "gridslam/geometry/pose2.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::matching {

/// Distance-field value of a cell that was never observed (any negative value means unknown).
constexpr float kUnknownDistance = -1.0F;

struct VerificationOptions {
  /// Verify accepted alignments against the grids when a VerificationInput is given.
  bool enabled = true;
  /// A transformed obstacle point agrees when a's distance field is at most this there [m]
  /// (2 cells of 5 cm).
  double agreement_distance = 0.1;
  /// Minimum fraction of the overlapping points that agree, in every checked direction [-].
  double min_agreement = 0.7;
  /// A transformed obstacle point contradicts the other map when it lands on an observed cell at
  /// least this far from the other map's obstacles [m].
  double contradiction_distance = 0.3;
  /// Maximum fraction of the overlapping points that contradict, in every checked direction;
  /// 1 disables the test [-].
  double max_contradiction = 0.1;
  /// Minimum number of obstacle points in the overlap, in every checked direction [-].
  int min_overlap_points = 50;
  /// Points used per direction at most (a regular subsample beyond it) [-].
  int max_points = 4000;
  /// Also check a's points against b's distance field when both are given.
  bool check_reverse = true;

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled, "Verify alignments by grid agreement when the grids are given");
    v("agreement_distance", agreement_distance,
      "Distance to the other map's nearest obstacle that counts as agreement [m]");
    v("min_agreement", min_agreement, "Minimum agreeing fraction of the overlap [-]");
    v("contradiction_distance", contradiction_distance,
      "Distance to the other map's obstacles beyond which a point contradicts it [m]");
    v("max_contradiction", max_contradiction,
      "Maximum contradicting fraction of the overlap (1 disables) [-]");
    v("min_overlap_points", min_overlap_points, "Minimum obstacle points in the overlap [-]");
    v("max_points", max_points, "Obstacle points checked per direction at most [-]");
    v("check_reverse", check_reverse, "Also check map a's points against map b");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(
        Require(agreement_distance >= 0.0, "matching.verification.agreement_distance >= 0"));
    GRIDSLAM_RETURN_IF_ERROR(Require(min_agreement >= 0.0 && min_agreement <= 1.0,
                                     "matching.verification.min_agreement in [0, 1]"));
    GRIDSLAM_RETURN_IF_ERROR(Require(contradiction_distance >= agreement_distance,
                                     "matching.verification.contradiction_distance >= "
                                     "agreement_distance"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_contradiction >= 0.0 && max_contradiction <= 1.0,
                                     "matching.verification.max_contradiction in [0, 1]"));
    GRIDSLAM_RETURN_IF_ERROR(
        Require(min_overlap_points >= 1, "matching.verification.min_overlap_points >= 1"));
    GRIDSLAM_RETURN_IF_ERROR(Require(max_points >= 1, "matching.verification.max_points >= 1"));
    return Status::Ok();
  }
};

/// What the verification looks at. The spans and grids are borrowed: they must outlive the call.
/// Distance fields hold, per cell, the Euclidean distance to the nearest obstacle cell [m]
/// (0 on obstacles) and a negative value (kUnknownDistance) on cells never observed; their
/// MapLimits are expressed in the key map's own frame (the same frame as its FeatureSet).
struct VerificationInput {
  std::span<const Eigen::Vector2d> points_b;  ///< Obstacle points of b, frame b [m].
  const Grid2D<float>* distance_a = nullptr;  ///< Distance field of a, frame a.
  std::span<const Eigen::Vector2d> points_a;  ///< Optional: obstacle points of a, frame a [m].
  const Grid2D<float>* distance_b = nullptr;  ///< Optional: distance field of b, frame b.
};

/// Agreement of one direction.
struct AgreementScore {
  int points = 0;         ///< Points looked up (after subsampling).
  int overlap = 0;        ///< Of them, landing on observed cells of the other map.
  int agreeing = 0;       ///< Of the overlap, within agreement_distance of an obstacle.
  int contradicting = 0;  ///< Of the overlap, beyond contradiction_distance of any obstacle.
  [[nodiscard]] double Agreement() const {
    return overlap > 0 ? static_cast<double>(agreeing) / overlap : 0.0;
  }
  [[nodiscard]] double Contradiction() const {
    return overlap > 0 ? static_cast<double>(contradicting) / overlap : 1.0;
  }
};

struct VerificationResult {
  bool accepted = false;
  bool enough_overlap = false;  ///< Overlap large enough in every checked direction.
  double agreement = 0.0;       ///< Smallest agreeing fraction over the checked directions.
  double contradiction = 1.0;   ///< Largest contradicting fraction over the checked directions.
  int overlap = 0;              ///< Smallest overlap over the checked directions.
  AgreementScore forward;       ///< b's points in a.
  AgreementScore reverse;       ///< a's points in b (if checked).
  bool reverse_checked = false;
};

/// Scores `points_src` (frame src) moved by T_dst_src against `distance_dst` (frame dst).
AgreementScore ScoreAgreement(std::span<const Eigen::Vector2d> points_src, const Pose2& T_dst_src,
                              const Grid2D<float>& distance_dst,
                              const VerificationOptions& options);

/// Verifies T_a_b (p_a = T_a_b * p_b). Contract: input.distance_a is set; the reverse direction
/// is checked when options.check_reverse and both points_a and distance_b are given.
VerificationResult VerifyAlignment(const Pose2& T_a_b, const VerificationInput& input,
                                   const VerificationOptions& options);

/// Centres of the cells with occupancy >= `min_occupancy` (0..100 scale, see OccupancyImage), in
/// the grid's frame [m]: the obstacle points for VerificationInput.
std::vector<Eigen::Vector2d> OccupiedCellCenters(const OccupancyImage& occupancy,
                                                 int min_occupancy = 50);

/// Sets `distance` to kUnknownDistance on every cell that is unknown in `occupancy`.
/// Contract: both grids have the same size.
void MarkUnknownCells(const OccupancyImage& occupancy, Grid2D<float>* distance);

}  // namespace gridslam::matching
