#include "gridslam/benchmark/pair_selection.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <utility>

#include "gridslam/common/angles.hpp"

namespace gridslam::benchmark {
namespace {

/// The pose of `truth` (sorted by time) nearest to `time`, if within `tolerance` [s].
std::optional<Pose2> LookUp(std::span<const eval::StampedPose> truth, Time time, double tolerance) {
  auto it = std::lower_bound(truth.begin(), truth.end(), time,
                             [](const eval::StampedPose& p, Time t) { return p.time < t; });
  std::optional<Pose2> best;
  double best_gap = tolerance;
  for (auto candidate : {it, it == truth.begin() ? it : std::prev(it)}) {
    if (candidate == truth.end()) {
      continue;
    }
    const double gap = std::abs(ToSeconds(candidate->time - time));
    if (gap <= best_gap) {
      best_gap = gap;
      best = candidate->pose;
    }
  }
  return best;
}

/// True frame of each key map in the world: T_world_key = T_world_base(t) * T_key_base(t)^-1
/// for the scan nearest the middle of its scans that has ground truth.
std::vector<std::optional<Pose2>> TrueKeyMapPoses(const KeyMapCatalog& catalog,
                                                  std::span<const eval::StampedPose> ground_truth,
                                                  double tolerance) {
  std::vector<eval::StampedPose> truth(ground_truth.begin(), ground_truth.end());
  std::stable_sort(truth.begin(), truth.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  std::vector<std::optional<Pose2>> centres;
  for (const KeyMapRecord& key_map : catalog.KeyMaps()) {
    std::optional<Pose2> centre;
    const int middle = (key_map.first_frame + key_map.last_frame) / 2;
    const int span = key_map.last_frame - key_map.first_frame;
    for (int step = 0; step <= span && !centre; ++step) {
      // middle, middle + 1, middle - 1, middle + 2, ...
      const int f = middle + ((step % 2 == 1) ? (step + 1) / 2 : -(step / 2));
      if (f < key_map.first_frame || f > key_map.last_frame) {
        continue;
      }
      const auto T_world_base =
          LookUp(truth, catalog.Frames()[static_cast<std::size_t>(f)].time, tolerance);
      if (T_world_base) {
        centre = *T_world_base * catalog.PoseInKeyMap(f, false).Inverse();
      }
    }
    centres.push_back(centre);
  }
  return centres;
}

/// The front end's error on one short relation; `begin` <= `end` are its two times.
struct FrontEndCheck {
  Time begin;
  Time end;
  double translation = 0.0;
  double rotation = 0.0;
};

/// The front end's errors on the relations no longer than truth_check_max_dt, sorted by begin.
std::vector<FrontEndCheck> FrontEndChecks(const KeyMapCatalog& catalog,
                                          std::span<const eval::Relation> relations,
                                          const AlignEvalOptions& options, bool laser) {
  auto pose = [&](int f) {
    const FrameRecord& frame = catalog.Frames()[static_cast<std::size_t>(f)];
    return laser ? frame.T_odom_base * frame.T_base_laser : frame.T_odom_base;
  };
  std::vector<FrontEndCheck> checks;
  for (const eval::Relation& relation : relations) {
    if (std::abs(ToSeconds(relation.t2 - relation.t1)) > options.truth_check_max_dt) {
      continue;
    }
    const int f1 = catalog.FindFrame(relation.t1, options.time_tolerance);
    const int f2 = catalog.FindFrame(relation.t2, options.time_tolerance);
    if (f1 < 0 || f2 < 0) {
      continue;
    }
    const Pose2 error = Between(relation.T_1_2, Between(pose(f1), pose(f2)));
    checks.push_back({std::min(relation.t1, relation.t2), std::max(relation.t1, relation.t2),
                      error.translation().norm(), std::abs(NormalizeAngle(error.theta()))});
  }
  std::sort(checks.begin(), checks.end(),
            [](const auto& a, const auto& b) { return a.begin < b.begin; });
  return checks;
}

/// Adds the checks lying within [from, to] to the pair's truth check.
void CheckTruth(std::span<const FrontEndCheck> checks, Time from, Time to, TestPair* pair) {
  auto it = std::lower_bound(checks.begin(), checks.end(), from,
                             [](const FrontEndCheck& c, Time t) { return c.begin < t; });
  for (; it != checks.end() && it->begin <= to; ++it) {
    if (it->end <= to) {
      ++pair->truth_checks;
      pair->truth_error_translation = std::max(pair->truth_error_translation, it->translation);
      pair->truth_error_rotation = std::max(pair->truth_error_rotation, it->rotation);
    }
  }
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// Component-wise median of nearby poses (angles unwrapped around the first one's).
Pose2 MedianPose(const std::vector<Pose2>& poses) {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> theta;
  for (const Pose2& pose : poses) {
    x.push_back(pose.x());
    y.push_back(pose.y());
    theta.push_back(poses.front().theta() + NormalizeAngle(pose.theta() - poses.front().theta()));
  }
  return {Median(x), Median(y), NormalizeAngle(Median(theta))};
}

}  // namespace

PositiveSelection SelectPositives(const KeyMapCatalog& catalog,
                                  std::span<const eval::Relation> relations,
                                  const AlignEvalOptions& options, bool relations_in_laser_frame) {
  PositiveSelection selection;
  std::map<std::pair<int, int>, std::size_t> seen;  // key-map pair -> index in pairs
  std::vector<std::vector<Pose2>> truths;           // per pair, from each of its relations
  const std::vector<FrontEndCheck> checks =
      FrontEndChecks(catalog, relations, options, relations_in_laser_frame);
  const Duration history = SecondsToDuration(options.truth_check_history);
  auto last_time = [&](int key_map) {
    const int f = catalog.KeyMaps()[static_cast<std::size_t>(key_map)].last_frame;
    return catalog.Frames()[static_cast<std::size_t>(f)].time;
  };
  for (const eval::Relation& relation : relations) {
    ++selection.relations;
    if (!(std::abs(ToSeconds(relation.t2 - relation.t1)) > options.min_time_gap)) {
      continue;
    }
    ++selection.revisits;
    const int f1 = catalog.FindFrame(relation.t1, options.time_tolerance);
    const int f2 = catalog.FindFrame(relation.t2, options.time_tolerance);
    if (f1 < 0 || f2 < 0) {
      ++selection.missing_scan;
      continue;
    }
    TestPair pair;
    pair.key_a = catalog.Frames()[static_cast<std::size_t>(f1)].key_map;
    pair.key_b = catalog.Frames()[static_cast<std::size_t>(f2)].key_map;
    if (pair.key_a == pair.key_b) {
      ++selection.same_key_map;
      continue;
    }
    pair.t1 = relation.t1;
    pair.t2 = relation.t2;
    pair.T_a_b_true = catalog.PoseInKeyMap(f1, relations_in_laser_frame) * relation.T_1_2 *
                      catalog.PoseInKeyMap(f2, relations_in_laser_frame).Inverse();
    pair.centre_distance = pair.T_a_b_true.translation().norm();
    if (pair.centre_distance > options.max_centre_distance) {
      ++selection.too_far;
      continue;
    }
    if (!options.include_shared && !catalog.WindowsSeparated(pair.key_a, pair.key_b)) {
      ++selection.shared;
      continue;
    }
    CheckTruth(checks, relation.t1 - history, last_time(pair.key_a), &pair);
    CheckTruth(checks, relation.t2 - history, last_time(pair.key_b), &pair);
    if (pair.truth_error_translation > options.truth_max_error ||
        pair.truth_error_rotation > DegToRad(options.truth_max_error_deg)) {
      ++selection.unreliable;
      continue;
    }
    const auto [it, inserted] =
        seen.emplace(std::make_pair(pair.key_a, pair.key_b), selection.pairs.size());
    if (!inserted) {
      ++selection.duplicates;
      TestPair& first = selection.pairs[it->second];
      truths[it->second].push_back(pair.T_a_b_true);
      first.truth_checks += pair.truth_checks;
      first.truth_error_translation =
          std::max(first.truth_error_translation, pair.truth_error_translation);
      first.truth_error_rotation = std::max(first.truth_error_rotation, pair.truth_error_rotation);
      continue;
    }
    truths.push_back({pair.T_a_b_true});
    selection.pairs.push_back(pair);
  }
  for (std::size_t k = 0; k < selection.pairs.size(); ++k) {
    TestPair& pair = selection.pairs[k];
    pair.relations = static_cast<int>(truths[k].size());
    pair.T_a_b_true = MedianPose(truths[k]);
    pair.centre_distance = pair.T_a_b_true.translation().norm();
    for (const Pose2& truth : truths[k]) {
      const Pose2 difference = Between(pair.T_a_b_true, truth);
      pair.truth_spread_translation =
          std::max(pair.truth_spread_translation, difference.translation().norm());
      pair.truth_spread_rotation =
          std::max(pair.truth_spread_rotation, std::abs(NormalizeAngle(difference.theta())));
    }
    selection.unchecked += pair.truth_checks == 0 ? 1 : 0;
  }
  return selection;
}

NegativeSelection SelectNegatives(const KeyMapCatalog& catalog,
                                  std::span<const eval::StampedPose> ground_truth,
                                  const AlignEvalOptions& options) {
  NegativeSelection selection;
  if (options.negatives <= 0) {
    return selection;
  }
  const std::vector<KeyMapRecord>& key_maps = catalog.KeyMaps();
  const int n = static_cast<int>(key_maps.size());
  selection.from_ground_truth = !ground_truth.empty();
  std::vector<std::optional<Pose2>> centres;
  if (selection.from_ground_truth) {
    centres = TrueKeyMapPoses(catalog, ground_truth, options.time_tolerance);
    selection.key_maps_with_truth = static_cast<int>(
        std::count_if(centres.begin(), centres.end(), [](const auto& c) { return c.has_value(); }));
  } else {
    for (const KeyMapRecord& key_map : key_maps) {
      centres.emplace_back(key_map.T_odom_key);
    }
  }
  // Reservoir sampling (Algorithm R) over the candidates in a fixed order: uniform, deterministic
  // for a seed, and memory bounded by the sample size.
  std::mt19937_64 rng(static_cast<std::uint64_t>(options.seed));
  const auto wanted = static_cast<std::size_t>(options.negatives);
  for (int a = 0; a < n; ++a) {
    if (!centres[static_cast<std::size_t>(a)]) {
      continue;
    }
    for (int b = a + 1; b < n; ++b) {
      if (!centres[static_cast<std::size_t>(b)]) {
        continue;
      }
      const Pose2& T_x_a = *centres[static_cast<std::size_t>(a)];
      const Pose2& T_x_b = *centres[static_cast<std::size_t>(b)];
      const double distance = (T_x_a.translation() - T_x_b.translation()).norm();
      double limit = options.negative_min_distance;
      if (!selection.from_ground_truth) {
        limit += options.negative_drift * std::abs(key_maps[static_cast<std::size_t>(b)].travel -
                                                   key_maps[static_cast<std::size_t>(a)].travel);
      }
      if (!(distance > limit)) {
        continue;
      }
      TestPair pair;
      pair.key_a = a;
      pair.key_b = b;
      pair.centre_distance = distance;
      pair.T_a_b_true = Between(T_x_a, T_x_b);
      const auto seen = static_cast<std::uint64_t>(selection.candidates++);
      if (selection.pairs.size() < wanted) {
        selection.pairs.push_back(pair);
      } else {
        const std::uint64_t slot = std::uniform_int_distribution<std::uint64_t>(0, seen)(rng);
        if (slot < wanted) {
          selection.pairs[static_cast<std::size_t>(slot)] = pair;
        }
      }
    }
  }
  std::sort(selection.pairs.begin(), selection.pairs.end(), [](const auto& x, const auto& y) {
    return std::make_pair(x.key_a, x.key_b) < std::make_pair(y.key_a, y.key_b);
  });
  return selection;
}

}  // namespace gridslam::benchmark
