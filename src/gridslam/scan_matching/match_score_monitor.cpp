#include "gridslam/scan_matching/match_score_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gridslam/common/check.hpp"

namespace gridslam::scan_matching {
namespace {

double Median(std::vector<double>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

MatchScoreMonitor::MatchScoreMonitor(const PoorMatchOptions& options)
    : options_(options),
      threshold_(-std::numeric_limits<double>::infinity()),
      usual_(std::numeric_limits<double>::infinity()) {
  GRIDSLAM_CHECK(options.Validate().ok());
  scores_.reserve(static_cast<std::size_t>(options.window));
}

void MatchScoreMonitor::Add(double score) {
  const auto window = static_cast<std::size_t>(options_.window);
  if (scores_.size() < window) {
    scores_.push_back(score);
  } else {
    scores_[next_] = score;
    next_ = (next_ + 1) % window;
  }
  if (scores_.size() < window) {
    return;
  }
  std::vector<double> work = scores_;
  const double median = Median(work);
  for (double& s : work) {
    s = std::abs(s - median);
  }
  const double sigma = 1.4826 * Median(work);
  threshold_ = median - std::max(options_.sigmas * sigma, options_.min_drop);
  usual_ = median - std::max(options_.usual_sigmas * sigma, options_.usual_floor);
}

bool MatchScoreMonitor::Poor(double score) const { return score < threshold_; }

const char* ToString(RescueVerdict verdict) {
  switch (verdict) {
    case RescueVerdict::kNone:
      return "none";
    case RescueVerdict::kNotClear:
      return "not_clear";
    case RescueVerdict::kAmbiguous:
      return "ambiguous";
    case RescueVerdict::kRescued:
      return "rescued";
  }
  return "unknown";
}

RescueChoice MatchScoreMonitor::Choose(const std::vector<ScoredPose>& candidates,
                                       const Pose2& prediction, double poor_score,
                                       const RescueRule& rule) const {
  RescueChoice choice;
  if (candidates.empty()) {
    return choice;
  }
  for (std::size_t k = 1; k < candidates.size(); ++k) {
    if (candidates[k].score > candidates[choice.best].score) {
      choice.best = k;
    }
  }
  const ScoredPose& best = candidates[choice.best];
  // Distance from the prediction in units of the search window.
  auto offset = [&](const Pose2& pose) {
    const Pose2 d = Between(prediction, pose);
    return d.translation().norm() / rule.window_xy + std::abs(d.theta()) / rule.window_theta;
  };
  const double best_offset = offset(best.pose);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Pose2 d = Between(best.pose, candidates[k].pose);
    const bool distinct =
        d.translation().norm() > rule.separation_xy || std::abs(d.theta()) > rule.separation_theta;
    const bool as_near = offset(candidates[k].pose) <= best_offset;
    if (distinct && as_near &&
        (!choice.has_rival || candidates[k].score > candidates[choice.rival].score)) {
      choice.has_rival = true;
      choice.rival = k;
    }
  }
  const bool clear =
      best.score >= rule.good_score && best.score > poor_score + rule.margin && Usual(best.score);
  const bool unique =
      !choice.has_rival || candidates[choice.rival].score <= best.score - rule.margin;
  choice.verdict = !clear    ? RescueVerdict::kNotClear
                   : !unique ? RescueVerdict::kAmbiguous
                             : RescueVerdict::kRescued;
  return choice;
}

}  // namespace gridslam::scan_matching
