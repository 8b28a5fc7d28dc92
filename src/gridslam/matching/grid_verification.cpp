#include "gridslam/matching/grid_verification.hpp"

#include <algorithm>

#include "gridslam/common/check.hpp"

namespace gridslam::matching {

AgreementScore ScoreAgreement(std::span<const Eigen::Vector2d> points_src, const Pose2& T_dst_src,
                              const Grid2D<float>& distance_dst,
                              const VerificationOptions& options) {
  AgreementScore score;
  const std::size_t n = points_src.size();
  if (n == 0) {
    return score;
  }
  const auto max_points = static_cast<std::size_t>(options.max_points);
  const std::size_t stride = (n + max_points - 1) / max_points;
  const MapLimits& limits = distance_dst.Limits();
  const auto agree = static_cast<float>(options.agreement_distance);
  const auto contradict = static_cast<float>(options.contradiction_distance);
  // Cell coordinates directly: q = (R p + t - origin) / resolution.
  const double inv_res = 1.0 / limits.Resolution();
  const Eigen::Matrix2d r = T_dst_src.Rotation() * inv_res;
  const Eigen::Vector2d t = (T_dst_src.translation() - limits.Origin()) * inv_res;
  const int width = limits.Width();
  const int height = limits.Height();
  const float* cells = distance_dst.data();
  for (std::size_t k = 0; k < n; k += stride) {
    ++score.points;
    const Eigen::Vector2d q = r * points_src[k] + t;
    if (!(q.x() >= 0.0 && q.y() >= 0.0 && q.x() < width && q.y() < height)) {
      continue;
    }
    const auto i = static_cast<long>(q.x());
    const auto j = static_cast<long>(q.y());
    const float d = cells[j * width + i];
    if (d < 0.0F) {
      continue;
    }
    ++score.overlap;
    score.agreeing += d <= agree ? 1 : 0;
    score.contradicting += d > contradict ? 1 : 0;
  }
  return score;
}

VerificationResult VerifyAlignment(const Pose2& T_a_b, const VerificationInput& input,
                                   const VerificationOptions& options) {
  GRIDSLAM_CHECK(input.distance_a != nullptr) << "VerifyAlignment needs map a's distance field";
  VerificationResult result;
  result.forward = ScoreAgreement(input.points_b, T_a_b, *input.distance_a, options);
  result.overlap = result.forward.overlap;
  result.agreement = result.forward.Agreement();
  result.contradiction = result.forward.Contradiction();
  result.reverse_checked =
      options.check_reverse && input.distance_b != nullptr && !input.points_a.empty();
  if (result.reverse_checked) {
    result.reverse = ScoreAgreement(input.points_a, T_a_b.Inverse(), *input.distance_b, options);
    result.overlap = std::min(result.overlap, result.reverse.overlap);
    result.agreement = std::min(result.agreement, result.reverse.Agreement());
    result.contradiction = std::max(result.contradiction, result.reverse.Contradiction());
  }
  result.enough_overlap = result.overlap >= options.min_overlap_points;
  result.accepted = result.enough_overlap && result.agreement >= options.min_agreement &&
                    result.contradiction <= options.max_contradiction;
  return result;
}

std::vector<Eigen::Vector2d> OccupiedCellCenters(const OccupancyImage& occupancy,
                                                 int min_occupancy) {
  std::vector<Eigen::Vector2d> points;
  for (int j = 0; j < occupancy.Height(); ++j) {
    for (int i = 0; i < occupancy.Width(); ++i) {
      if (occupancy(i, j) >= min_occupancy) {
        points.push_back(occupancy.Limits().CellCenter({i, j}));
      }
    }
  }
  return points;
}

void MarkUnknownCells(const OccupancyImage& occupancy, Grid2D<float>* distance) {
  GRIDSLAM_CHECK(distance != nullptr && distance->Width() == occupancy.Width() &&
                 distance->Height() == occupancy.Height())
      << "MarkUnknownCells: grids of different sizes";
  for (std::size_t k = 0; k < occupancy.size(); ++k) {
    if (occupancy.data()[k] == kUnknownCell) {
      distance->data()[k] = kUnknownDistance;
    }
  }
}

}  // namespace gridslam::matching
