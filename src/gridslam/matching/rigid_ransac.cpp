#include "gridslam/matching/rigid_ransac.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "gridslam/common/angles.hpp"

namespace gridslam::matching {
namespace {

struct Hypothesis {
  double cos_theta = 1.0;
  double sin_theta = 0.0;
  double theta = 0.0;
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
};

struct Score {
  int inliers = 0;
  double sum_squared = 0.0;  // of the inliers' residuals
  [[nodiscard]] bool BetterThan(const Score& other) const {
    return inliers > other.inliers || (inliers == other.inliers && sum_squared < other.sum_squared);
  }
};

class Estimator {
 public:
  Estimator(const Correspondences& c, const RansacOptions& options)
      : c_(c),
        options_(options),
        radius2_(options.inlier_radius * options.inlier_radius),
        separation2_(options.min_pair_separation * options.min_pair_separation),
        use_rotation_(options.max_orientation_difference > 0.0 && c.rotation.size() == c.a.size()) {
  }

  // The 2-point hypothesis of matches i and j, unless a pre-check rejects the pair.
  bool MakeHypothesis(int i, int j, Hypothesis* h) const {
    const Eigen::Vector2d va = A(i) - A(j);
    const Eigen::Vector2d vb = B(i) - B(j);
    const double la2 = va.squaredNorm();
    const double lb2 = vb.squaredNorm();
    if (la2 < separation2_ || lb2 < separation2_ || la2 == 0.0 || lb2 == 0.0) {
      return false;
    }
    // Both members are inliers only if the lengths differ by less than 2 * inlier_radius.
    if (std::abs(std::sqrt(la2) - std::sqrt(lb2)) >= 2.0 * options_.inlier_radius) {
      return false;
    }
    h->theta = std::atan2(vb.x() * va.y() - vb.y() * va.x(), vb.dot(va));
    if (use_rotation_ &&
        (std::abs(NormalizeAngle(h->theta - Rotation(i))) > options_.max_orientation_difference ||
         std::abs(NormalizeAngle(h->theta - Rotation(j))) > options_.max_orientation_difference)) {
      return false;
    }
    h->cos_theta = std::cos(h->theta);
    h->sin_theta = std::sin(h->theta);
    const Eigen::Vector2d mid_a = 0.5 * (A(i) + A(j));
    const Eigen::Vector2d mid_b = 0.5 * (B(i) + B(j));
    h->t = mid_a - Rotate(*h, mid_b);
    return true;
  }

  [[nodiscard]] Score Evaluate(const Hypothesis& h) const {
    Score s;
    for (int k = 0; k < c_.size(); ++k) {
      const double e2 = (Rotate(h, B(k)) + h.t - A(k)).squaredNorm();
      if (e2 < radius2_) {
        ++s.inliers;
        s.sum_squared += e2;
      }
    }
    return s;
  }

  [[nodiscard]] std::vector<int> Inliers(const Pose2& T_a_b) const {
    std::vector<int> inliers;
    for (int k = 0; k < c_.size(); ++k) {
      if ((T_a_b * B(k) - A(k)).squaredNorm() < radius2_) {
        inliers.push_back(k);
      }
    }
    return inliers;
  }

 private:
  static Eigen::Vector2d Rotate(const Hypothesis& h, const Eigen::Vector2d& p) {
    return {h.cos_theta * p.x() - h.sin_theta * p.y(), h.sin_theta * p.x() + h.cos_theta * p.y()};
  }
  [[nodiscard]] const Eigen::Vector2d& A(int k) const { return c_.a[static_cast<std::size_t>(k)]; }
  [[nodiscard]] const Eigen::Vector2d& B(int k) const { return c_.b[static_cast<std::size_t>(k)]; }
  [[nodiscard]] double Rotation(int k) const { return c_.rotation[static_cast<std::size_t>(k)]; }

  const Correspondences& c_;
  const RansacOptions& options_;
  double radius2_;
  double separation2_;
  bool use_rotation_;
};

// Hypotheses needed to draw an all-inlier pair with probability `confidence` when a fraction
// `w` of the matches are inliers.
int AdaptiveIterations(int inliers, int matches, const RansacOptions& options) {
  const double w = static_cast<double>(inliers) / static_cast<double>(matches);
  const double p_pair = w * w;
  if (p_pair >= 1.0) {
    return 1;
  }
  const double n = std::ceil(std::log(1.0 - options.confidence) / std::log(1.0 - p_pair));
  return n < static_cast<double>(options.max_iterations) ? static_cast<int>(n)
                                                         : options.max_iterations;
}

}  // namespace

RansacResult EstimateRigidRansac(const Correspondences& c, const RansacOptions& options) {
  RansacResult result;
  const int m = c.size();
  if (m < 2 || static_cast<int>(c.b.size()) != m) {
    return result;
  }
  const Estimator estimator(c, options);
  Hypothesis best_h;
  Score best;
  Hypothesis h;
  const auto consider = [&](int i, int j) {
    if (!estimator.MakeHypothesis(i, j, &h)) {
      return false;
    }
    const Score s = estimator.Evaluate(h);
    if (s.BetterThan(best)) {
      best = s;
      best_h = h;
      return true;
    }
    return false;
  };

  result.exhaustive = m <= options.exhaustive_max_matches;
  if (result.exhaustive) {
    for (int i = 0; i < m; ++i) {
      for (int j = i + 1; j < m; ++j) {
        consider(i, j);
        ++result.iterations;
      }
    }
  } else {
    std::mt19937 rng(static_cast<std::mt19937::result_type>(options.seed));
    const auto um = static_cast<std::mt19937::result_type>(m);
    int needed = options.max_iterations;
    while (result.iterations < needed) {
      ++result.iterations;
      // Modulo keeps the stream portable across standard libraries (tiny bias, irrelevant here).
      const int i = static_cast<int>(rng() % um);
      int j = static_cast<int>(rng() % (um - 1));
      j += j >= i ? 1 : 0;
      if (consider(i, j)) {
        needed = AdaptiveIterations(best.inliers, m, options);
      }
    }
  }
  if (best.inliers < 2) {
    return result;
  }

  result.found = true;
  result.T_a_b_hypothesis = Pose2(best_h.t, best_h.theta);
  result.hypothesis_inliers = best.inliers;
  result.T_a_b = result.T_a_b_hypothesis;
  result.inliers = estimator.Inliers(result.T_a_b);
  for (int round = 0; round < options.refine_iterations; ++round) {
    const Pose2 refined = FitRigid2D(c, result.inliers);
    std::vector<int> inliers = estimator.Inliers(refined);
    if (inliers.size() < 2) {
      break;
    }
    result.T_a_b = refined;
    result.inliers = std::move(inliers);
  }
  return result;
}

}  // namespace gridslam::matching
