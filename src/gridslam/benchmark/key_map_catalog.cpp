#include "gridslam/benchmark/key_map_catalog.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "gridslam/common/check.hpp"
#include "gridslam/scan_matching/front_end.hpp"

namespace gridslam::benchmark {
namespace {

KeyMapRecord Record(const keymap::KeyMap& key_map, int first_frame, int last_frame, double travel) {
  KeyMapRecord record;
  record.id = key_map.id;
  record.T_odom_key = key_map.T_odom_key;
  const MapLimits& limits = key_map.log_odds.Limits();
  record.window_min = key_map.T_odom_key.translation() + limits.Origin();
  record.window_max =
      record.window_min + Eigen::Vector2d(limits.Width(), limits.Height()) * limits.Resolution();
  record.first_frame = first_frame;
  record.last_frame = last_frame;
  record.travel = travel;
  return record;
}

}  // namespace

KeyMapCatalog KeyMapCatalog::Build(std::span<const Frame> frames,
                                   const scan_matching::FrontEndOptions& options,
                                   const KeyMapCallback& on_key_map) {
  const auto start = std::chrono::steady_clock::now();
  KeyMapCatalog catalog;
  catalog.frames_.reserve(frames.size());
  scan_matching::FrontEnd front_end(options);
  int first_unassigned = 0;
  double travel = 0.0;
  // Each key map holds the scans added since the previous one (key_map_builder.hpp).
  auto finish = [&](keymap::KeyMap&& key_map) {
    const int last = static_cast<int>(catalog.frames_.size()) - 1;
    GRIDSLAM_CHECK(key_map.id == static_cast<int>(catalog.key_maps_.size()))
        << "key maps are numbered in order";
    GRIDSLAM_CHECK(static_cast<int>(key_map.scans.size()) == last - first_unassigned + 1)
        << "a key map holds the scans since the previous one";
    for (int f = first_unassigned; f <= last; ++f) {
      catalog.frames_[static_cast<std::size_t>(f)].key_map = key_map.id;
    }
    catalog.key_maps_.push_back(Record(key_map, first_unassigned, last, travel));
    first_unassigned = last + 1;
    if (on_key_map) {
      on_key_map(std::move(key_map));
    }
  };
  for (const Frame& frame : frames) {
    scan_matching::FrontEndStep step = front_end.AddFrame(frame);
    if (!catalog.frames_.empty()) {
      travel += (step.T_odom_base.translation() - catalog.frames_.back().T_odom_base.translation())
                    .norm();
    }
    catalog.frames_.push_back({frame.time, step.T_odom_base, frame.T_base_laser, -1, travel});
    if (step.key_map.has_value()) {
      finish(std::move(*step.key_map));
    }
  }
  if (auto last = front_end.Finish(); last.has_value()) {
    finish(std::move(*last));
  }
  catalog.by_time_.resize(catalog.frames_.size());
  for (std::size_t i = 0; i < catalog.by_time_.size(); ++i) {
    catalog.by_time_[i] = static_cast<int>(i);
  }
  std::stable_sort(catalog.by_time_.begin(), catalog.by_time_.end(), [&](int a, int b) {
    return catalog.frames_[static_cast<std::size_t>(a)].time <
           catalog.frames_[static_cast<std::size_t>(b)].time;
  });
  catalog.seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return catalog;
}

int KeyMapCatalog::FindFrame(Time time, double tolerance) const {
  const auto time_of = [&](int index) { return frames_[static_cast<std::size_t>(index)].time; };
  auto it = std::lower_bound(by_time_.begin(), by_time_.end(), time,
                             [&](int index, Time t) { return time_of(index) < t; });
  int best = -1;
  double best_gap = tolerance;
  for (auto candidate : {it, it == by_time_.begin() ? it : std::prev(it)}) {
    if (candidate == by_time_.end()) {
      continue;
    }
    const double gap = std::abs(ToSeconds(time_of(*candidate) - time));
    if (gap <= best_gap) {
      best_gap = gap;
      best = *candidate;
    }
  }
  return best;
}

Pose2 KeyMapCatalog::PoseInKeyMap(int frame, bool laser) const {
  const FrameRecord& record = frames_.at(static_cast<std::size_t>(frame));
  const KeyMapRecord& key_map = key_maps_.at(static_cast<std::size_t>(record.key_map));
  const Pose2 T_key_base = key_map.T_odom_key.Inverse() * record.T_odom_base;
  return laser ? T_key_base * record.T_base_laser : T_key_base;
}

bool KeyMapCatalog::WindowsSeparated(int a, int b) const {
  if (a > b) {
    std::swap(a, b);
  }
  Eigen::Vector2d lo = key_maps_.at(static_cast<std::size_t>(a)).window_min;
  Eigen::Vector2d hi = key_maps_.at(static_cast<std::size_t>(a)).window_max;
  for (int k = a + 1; k <= b; ++k) {
    const KeyMapRecord& record = key_maps_.at(static_cast<std::size_t>(k));
    lo = lo.cwiseMax(record.window_min);
    hi = hi.cwiseMin(record.window_max);
    if ((lo.array() >= hi.array()).any()) {
      return true;
    }
  }
  return false;
}

}  // namespace gridslam::benchmark
