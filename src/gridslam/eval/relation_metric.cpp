#include "gridslam/eval/relation_metric.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace gridslam::eval {
namespace {

/// Index of the trajectory pose nearest to `t` within `tolerance`, in `order` (sorted by time).
std::optional<std::size_t> Lookup(const std::vector<StampedPose>& trajectory,
                                  const std::vector<std::size_t>& order, Time t,
                                  Duration tolerance) {
  auto it = std::lower_bound(order.begin(), order.end(), t,
                             [&](std::size_t i, Time value) { return trajectory[i].time < value; });
  std::optional<std::size_t> best;
  Duration best_gap = Duration::max();
  auto consider = [&](std::vector<std::size_t>::const_iterator c) {
    const Duration gap =
        trajectory[*c].time > t ? trajectory[*c].time - t : t - trajectory[*c].time;
    if (gap < best_gap) {
      best_gap = gap;
      best = *c;
    }
  };
  if (it != order.end()) {
    consider(it);
  }
  if (it != order.begin()) {
    // The first of a run of equal times before `t`.
    auto prev = it - 1;
    const Time prev_time = trajectory[*prev].time;
    while (prev != order.begin() && trajectory[*(prev - 1)].time == prev_time) {
      --prev;
    }
    consider(prev);
  }
  if (!best || best_gap > tolerance) {
    return std::nullopt;
  }
  return best;
}

}  // namespace

MeanStd ComputeMeanStd(const std::vector<double>& values) {
  MeanStd out;
  if (values.empty()) {
    return out;
  }
  const double n = static_cast<double>(values.size());
  double sum = 0.0;
  for (double v : values) {
    sum += v;
  }
  out.mean = sum / n;
  if (values.size() >= 2) {
    double ss = 0.0;
    for (double v : values) {
      ss += (v - out.mean) * (v - out.mean);
    }
    out.std = std::sqrt(ss / (n - 1.0));
  }
  return out;
}

Pose2 RelationErrorPose(const Pose2& estimate, const Pose2& truth) {
  return estimate.Inverse() * truth;
}

RelationMetrics EvaluateRelations(const std::vector<Relation>& relations,
                                  const std::vector<StampedPose>& trajectory,
                                  const EvalOptions& options) {
  std::vector<std::size_t> order(trajectory.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    order[i] = i;
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return trajectory[a].time < trajectory[b].time;
  });
  const Duration tolerance = SecondsToDuration(options.tolerance);

  RelationMetrics m;
  m.total = static_cast<long>(relations.size());
  std::vector<double> t_abs, t_sq, r_abs, r_sq;
  for (const Relation& r : relations) {
    const double dt = std::abs(ToSeconds(r.t2 - r.t1));
    if (dt < options.min_dt || (options.max_dt > 0.0 && dt >= options.max_dt)) {
      ++m.filtered;
      continue;
    }
    const auto i1 = Lookup(trajectory, order, r.t1, tolerance);
    const auto i2 = Lookup(trajectory, order, r.t2, tolerance);
    if (!i1 || !i2) {
      ++m.missing;
      continue;
    }
    const Pose2 estimate = Between(trajectory[*i1].pose, trajectory[*i2].pose);
    const Pose2 error = RelationErrorPose(estimate, r.T_1_2);
    RelationError e{r, error.translation().norm(), std::abs(error.theta())};
    m.errors.push_back(e);
    const double deg = RadToDeg(e.rotation);
    t_abs.push_back(e.translation);
    t_sq.push_back(e.translation * e.translation);
    r_abs.push_back(deg);
    r_sq.push_back(deg * deg);
  }
  m.used = static_cast<long>(m.errors.size());
  m.translation = ComputeMeanStd(t_abs);
  m.translation_sq = ComputeMeanStd(t_sq);
  m.rotation_deg = ComputeMeanStd(r_abs);
  m.rotation_sq_deg2 = ComputeMeanStd(r_sq);
  return m;
}

}  // namespace gridslam::eval
