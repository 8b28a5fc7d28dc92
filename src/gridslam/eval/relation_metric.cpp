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

/// The pose at `t` interpolated between the trajectory poses just before and just after it, if
/// both exist and lie at most `max_gap` apart (0 = any gap).
std::optional<Pose2> InterpolateAt(const std::vector<StampedPose>& trajectory,
                                   const std::vector<std::size_t>& order, Time t, double max_gap) {
  auto after = std::upper_bound(order.begin(), order.end(), t, [&](Time value, std::size_t i) {
    return value < trajectory[i].time;
  });
  if (after == order.end() || after == order.begin()) {
    return std::nullopt;
  }
  auto before = after - 1;
  // The first of a run of equal times (duplicates use the first, as Lookup).
  while (before != order.begin() && trajectory[*(before - 1)].time == trajectory[*before].time) {
    --before;
  }
  const StampedPose& a = trajectory[*before];
  const StampedPose& b = trajectory[*after];
  const double gap = ToSeconds(b.time - a.time);
  if (gap <= 0.0 || (max_gap > 0.0 && gap > max_gap)) {
    return std::nullopt;
  }
  return Interpolate(a.pose, b.pose, ToSeconds(t - a.time) / gap);
}

/// The pose at `t`: exact (within the tolerance) or interpolated if allowed; `interpolated` is
/// set when it was interpolated.
std::optional<Pose2> PoseAt(const std::vector<StampedPose>& trajectory,
                            const std::vector<std::size_t>& order, Time t, Duration tolerance,
                            const EvalOptions& options, bool& interpolated) {
  if (const auto i = Lookup(trajectory, order, t, tolerance)) {
    return trajectory[*i].pose;
  }
  if (!options.interpolate) {
    return std::nullopt;
  }
  auto pose = InterpolateAt(trajectory, order, t, options.max_interpolation_gap);
  interpolated = interpolated || pose.has_value();
  return pose;
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
    bool interpolated = false;
    const auto p1 = PoseAt(trajectory, order, r.t1, tolerance, options, interpolated);
    const auto p2 = PoseAt(trajectory, order, r.t2, tolerance, options, interpolated);
    if (!p1 || !p2) {
      ++m.missing;
      continue;
    }
    if (interpolated) {
      ++m.interpolated;
    }
    const Pose2 estimate = Between(*p1, *p2);
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
